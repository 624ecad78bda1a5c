// The C API (ncjoule.h) over the C++ library: exceptions and C++ types stop here.
#include "ncjoule.h"

#include <cstdlib>
#include <exception>
#include <fstream>
#include <iterator>
#include <memory>
#include <string>
#include <vector>

#include "ncjoule/estimate.hpp"
#include "ncjoule/profile.hpp"
#include "ncjoule/report.hpp"

struct ncjoule_context {
  ncjoule::MachineProfile machine;
  ncjoule::EstimateOptions options;
};

struct ncjoule_result {
  ncjoule::Estimate estimate;
  std::string json;
  std::vector<std::string> diagnostics;
};

namespace {

thread_local std::string last_error;

void fail(std::string message) {
  last_error = std::move(message);
}

// Runs `body`, turning any exception into last_error and the given failure value.
template <typename T, typename Body> T guarded(T failure, Body body) {
  try {
    return body();
  } catch (const std::exception& e) {
    fail(e.what());
  } catch (...) {
    fail("unknown error");
  }
  return failure;
}

ncjoule_result* make_result(ncjoule_context* context, const ncjoule::SourceFile& source) {
  auto result = std::make_unique<ncjoule_result>();
  result->estimate = ncjoule::estimate_program(source, context->machine, context->options);
  for (const ncjoule::Diagnostic& d : result->estimate.diagnostics)
    result->diagnostics.push_back(ncjoule::format_diagnostic(d));
  if (result->estimate.failed) {
    std::string why = source.path + " cannot be estimated";
    for (const std::string& d : result->diagnostics)
      if (d.find(": error: ") != std::string::npos) why += "\n" + d;
    fail(why);
    return nullptr;
  }
  result->json = ncjoule::estimate_json(result->estimate, context->machine);
  return result.release();
}

} // namespace

extern "C" {

const char* ncjoule_version(void) {
  return "0.1.0";
}

const char* ncjoule_last_error(void) {
  return last_error.c_str();
}

ncjoule_context* ncjoule_context_create(const char* machine_profile_path) {
  if (!machine_profile_path) return fail("no machine profile given"), nullptr;
  return guarded<ncjoule_context*>(nullptr, [&] {
    auto context = std::make_unique<ncjoule_context>();
    context->machine = ncjoule::load_profile(machine_profile_path);
    return context.release();
  });
}

void ncjoule_context_destroy(ncjoule_context* context) {
  delete context;
}

int ncjoule_context_set_stock(ncjoule_context* context, const char* stock) {
  if (!context) return fail("no context"), -1;
  if (!stock || !*stock) {
    context->options.stock.reset();
    return 0;
  }
  std::string error;
  auto spec = ncjoule::parse_stock_spec(stock, &error);
  if (!spec) return fail(std::string("bad stock '") + stock + "': " + error), -1;
  context->options.stock = *spec;
  return 0;
}

void ncjoule_context_set_removal(ncjoule_context* context, int enabled) {
  if (context) context->options.simulate_removal = enabled != 0;
}

int ncjoule_context_set_dialect(ncjoule_context* context, const char* dialect) {
  if (!context) return fail("no context"), -1;
  if (!dialect || !*dialect) {
    context->options.dialect.reset();
    return 0;
  }
  auto d = ncjoule::find_dialect(dialect);
  if (!d) return fail(std::string("unknown dialect '") + dialect + "'"), -1;
  context->options.dialect = *d;
  return 0;
}

ncjoule_result* ncjoule_estimate_file(ncjoule_context* context, const char* path) {
  if (!context || !path) return fail("no context or no path"), nullptr;
  return guarded<ncjoule_result*>(nullptr, [&]() -> ncjoule_result* {
    std::ifstream in(path, std::ios::binary);
    if (!in) return fail(std::string("cannot read ") + path), nullptr;
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    return make_result(context, ncjoule::make_source(path, std::move(text)));
  });
}

ncjoule_result* ncjoule_estimate_string(ncjoule_context* context, const char* text, size_t length,
                                        const char* name) {
  if (!context || (!text && length)) return fail("no context or no text"), nullptr;
  return guarded<ncjoule_result*>(nullptr, [&] {
    return make_result(context, ncjoule::make_source(name ? name : "<string>",
                                                     std::string(text ? text : "", length)));
  });
}

void ncjoule_result_destroy(ncjoule_result* result) {
  delete result;
}

int ncjoule_result_totals(const ncjoule_result* result, ncjoule_totals* totals) {
  if (!result || !totals) return fail("no result or no totals"), -1;
  const ncjoule::EnergyResult& e = result->estimate.energy;
  totals->time_s = result->estimate.timeline.total_s;
  totals->energy_j = e.energy_j;
  totals->removed_mm3 = e.removed_mm3;
  totals->sec_j_mm3 = e.sec_j_mm3;
  totals->co2_kg = e.co2_kg;
  totals->cost = e.cost;
  totals->mean_power_w = e.mean_power_w;
  totals->peak_power_w = e.peak_power_w;
  return 0;
}

size_t ncjoule_result_block_count(const ncjoule_result* result) {
  return result ? result->estimate.lines.size() : 0;
}

int ncjoule_result_block(const ncjoule_result* result, size_t index, ncjoule_block* block) {
  if (!result || !block || index >= result->estimate.lines.size())
    return fail("block index out of range"), -1;
  const ncjoule::LineSummary& s = result->estimate.lines[index];
  block->line = s.line + 1;
  block->kind = s.kind.c_str();
  block->start_s = s.start_s;
  block->time_s = s.time_s;
  block->removed_mm3 = s.removed_mm3;
  block->mrr_mm3_s = s.time_s > 0 ? s.removed_mm3 / s.time_s : 0;
  block->power_w = s.time_s > 0 ? s.energy_j / s.time_s : 0;
  block->power_peak_w = s.power_peak_w;
  block->energy_j = s.energy_j;
  return 0;
}

size_t ncjoule_result_diagnostic_count(const ncjoule_result* result) {
  return result ? result->diagnostics.size() : 0;
}

const char* ncjoule_result_diagnostic(const ncjoule_result* result, size_t index) {
  if (!result || index >= result->diagnostics.size()) return nullptr;
  return result->diagnostics[index].c_str();
}

const char* ncjoule_result_json(const ncjoule_result* result) {
  return result ? result->json.c_str() : nullptr;
}

void ncjoule_free(void* pointer) {
  std::free(pointer);
}

} // extern "C"
