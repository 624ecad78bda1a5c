// The C API (ncjoule.h) over the C++ library: exceptions and C++ types stop here.
#include "ncjoule.h"

#include <cstdlib>
#include <cstring>
#include <exception>
#include <fstream>
#include <iterator>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "in_place.hpp"
#include "ncjoule/annotate.hpp"
#include "ncjoule/estimate.hpp"
#include "ncjoule/profile.hpp"
#include "ncjoule/report.hpp"
#include "ncjoule/text_file.hpp"
#include "output_file.hpp"

#include <sys/stat.h>

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

// The annotated program, or nullopt with last_error set.
std::optional<ncjoule::AnnotatedProgram>
annotated(ncjoule_context* context, const std::string& name, const std::string& text) {
  ncjoule::AnnotatedProgram result =
      ncjoule::annotate_program(name, text, context->machine, context->options);
  if (result.estimate.failed) {
    std::string errors;
    for (const ncjoule::Diagnostic& d : result.estimate.diagnostics)
      if (d.severity == ncjoule::Severity::Error) errors += "\n" + ncjoule::format_diagnostic(d);
    fail(name + " could not be estimated" + errors);
    return std::nullopt;
  }
  return result;
}

// Whether two paths name the same existing file.
bool same_file(const char* a, const char* b) {
  struct stat sa {
  }, sb{};
  return ::stat(a, &sa) == 0 && ::stat(b, &sb) == 0 && sa.st_dev == sb.st_dev &&
         sa.st_ino == sb.st_ino;
}

std::optional<std::string> read_file(const char* path) {
  std::vector<ncjoule::Diagnostic> problems;
  auto text =
      ncjoule::read_text_file(path, "an NC file", problems, ncjoule::kDefaultMaxProgramBytes);
  if (!text) fail(ncjoule::format_diagnostic(problems.front()));
  return text;
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
  std::vector<ncjoule::Diagnostic> problems;
  auto spec = ncjoule::parse_stock_spec(stock, &problems, {std::string("stock '") + stock + "'"});
  if (!spec) return fail(ncjoule::format_diagnostic(problems.front())), -1;
  context->options.stock = *spec;
  return 0;
}

void ncjoule_context_set_removal(ncjoule_context* context, int enabled) {
  if (context) context->options.simulate_removal = enabled != 0;
}

int ncjoule_context_set_dialect(ncjoule_context* context, const char* dialect) {
  if (!context) return fail("no context"), -1;
  context->options.detect_dialect = dialect && std::strcmp(dialect, "auto") == 0;
  if (!dialect || !*dialect || context->options.detect_dialect) {
    context->options.dialect.reset();
    return 0;
  }
  auto d = ncjoule::find_dialect(dialect);
  if (!d) return fail(std::string("unknown dialect '") + dialect + "'"), -1;
  context->options.dialect = *d;
  return 0;
}

void ncjoule_context_set_progress(ncjoule_context* context, ncjoule_progress_callback callback,
                                  void* user) {
  if (!context) return;
  if (!callback) {
    context->options.progress = nullptr;
    return;
  }
  context->options.progress = [callback, user](double fraction) { callback(fraction, user); };
}

int ncjoule_context_add_tool(ncjoule_context* context, const char* tool) {
  if (!context || !tool) return fail("no context or no tool"), -1;
  std::vector<ncjoule::Diagnostic> problems;
  const auto parsed =
      ncjoule::parse_tool_spec(tool, &problems, {std::string("tool '") + tool + "'"});
  if (!parsed) return fail(ncjoule::format_diagnostic(problems.front())), -1;
  context->options.tools[parsed->number] = *parsed;
  return 0;
}

void ncjoule_context_clear_tools(ncjoule_context* context) {
  if (context) context->options.tools.clear();
}

int ncjoule_context_set_default_tool(ncjoule_context* context, const char* tool) {
  if (!context) return fail("no context"), -1;
  if (!tool || !*tool) {
    context->options.default_tool.reset();
    return 0;
  }
  std::vector<ncjoule::Diagnostic> problems;
  const auto parsed = ncjoule::parse_tool_spec(std::string("0:") + tool, &problems,
                                               {std::string("default tool '") + tool + "'"});
  if (!parsed) return fail(ncjoule::format_diagnostic(problems.front())), -1;
  context->options.default_tool = *parsed;
  return 0;
}

int ncjoule_context_set_tool_table(ncjoule_context* context, const char* path, int inch) {
  if (!context) return fail("no context"), -1;
  return guarded<int>(-1, [&] {
    if (!path || !*path) {
      context->options.tool_table.clear();
      context->options.tool_table_path.clear();
      return 0;
    }
    auto text = read_file(path);
    if (!text) return -1;
    std::vector<ncjoule::Diagnostic> diagnostics;
    ncjoule::ToolTable table = ncjoule::parse_tool_table(
        ncjoule::make_source(path, std::move(*text)), inch != 0, diagnostics);
    for (const ncjoule::Diagnostic& d : diagnostics)
      if (d.severity == ncjoule::Severity::Error) return fail(ncjoule::format_diagnostic(d)), -1;
    context->options.tool_table = std::move(table);
    context->options.tool_table_path = path;
    return 0;
  });
}

int ncjoule_context_set_job(ncjoule_context* context, const char* path) {
  if (!context) return fail("no context"), -1;
  if (!path || !*path) return 0;
  return guarded<int>(-1, [&] {
    std::vector<ncjoule::Diagnostic> diagnostics;
    const auto job = ncjoule::read_job_file(path, diagnostics);
    if (!job) {
      std::string why;
      for (const ncjoule::Diagnostic& d : diagnostics)
        if (d.severity == ncjoule::Severity::Error)
          why += (why.empty() ? "" : "\n") + ncjoule::format_diagnostic(d);
      return fail(why.empty() ? std::string("cannot read job file ") + path : why), -1;
    }
    if (job->stock) context->options.stock = job->stock;
    context->options.tools = job->tools;
    return 0;
  });
}

ncjoule_result* ncjoule_estimate_file(ncjoule_context* context, const char* path) {
  if (!context || !path) return fail("no context or no path"), nullptr;
  return guarded<ncjoule_result*>(nullptr, [&]() -> ncjoule_result* {
    auto text = read_file(path);
    if (!text) return nullptr;
    return make_result(context, ncjoule::make_source(path, std::move(*text)));
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
  totals->time_s = result->estimate.time_s;
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
  block->kind = ncjoule::line_kind_name(s.kind);
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

char* ncjoule_annotate_string(ncjoule_context* context, const char* text, size_t length,
                              const char* name, size_t* out_length) {
  if (!context || (!text && length)) return fail("no context or no text"), nullptr;
  return guarded<char*>(nullptr, [&]() -> char* {
    auto result =
        annotated(context, name ? name : "<string>", std::string(text ? text : "", length));
    if (!result) return nullptr;
    const std::string* annotated = &result->text;
    char* out = static_cast<char*>(std::malloc(annotated->size() + 1));
    if (!out) return fail("out of memory"), nullptr;
    std::memcpy(out, annotated->data(), annotated->size());
    out[annotated->size()] = '\0';
    if (out_length) *out_length = annotated->size();
    return out;
  });
}

int ncjoule_annotate_file(ncjoule_context* context, const char* in_path, const char* out_path) {
  if (!context || !in_path) return fail("no context or no input path"), -1;
  return guarded<int>(-1, [&] {
    const bool in_place = !out_path || !*out_path || std::strcmp(out_path, in_path) == 0 ||
                          same_file(in_path, out_path);
    // In place, as `ncjoule annotate --in-place`: never a link's target, never a file another
    // program is still writing (checked before the read and again right before the rename).
    ncjoule::cli::FileStamp stamp;
    if (in_place) {
      if (std::string why = ncjoule::cli::in_place_refusal(in_path, false, stamp); !why.empty())
        return fail(why + "; " + in_path + " is untouched"), -1;
    }
    auto text = read_file(in_path);
    if (!text) return -1;
    auto result = annotated(context, in_path, *text);
    if (!result) return -1;
    if (in_place && result->text == *text) return 0; // already annotated this way
    const ncjoule::cli::InPlaceCheck check{stamp, result->estimate.program_end};
    const std::string target = in_place ? in_path : out_path;
    if (const std::string error = ncjoule::cli::write_output_file(
            target, result->text, {in_place ? &check : nullptr, nullptr});
        !error.empty())
      return fail(error + (in_place ? std::string("; ") + in_path + " is untouched" : "")), -1;
    return 0;
  });
}

void ncjoule_free(void* pointer) {
  std::free(pointer);
}

} // extern "C"
