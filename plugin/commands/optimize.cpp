// `ncjoule optimize PROGRAM [--stock ...] [-m PROFILE] -o OUT`: writes a faster alternative of a
// posted program, changing only feed moves that run clear of the in-process stock (air feeds,
// retracts and links as rapids) and, with --load-feeds, the feeds of cutting blocks to a spindle
// load target, and prints what that saves by operation (docs/optimize.md).
//
// Only with a known stock (given, or read from the CAM): what is clear of a guessed stock need
// not be clear of the real one. The original is never written; the optimized text is estimated
// again with the same stock before it is written, and nothing is written unless it removes the
// same volume (within 0.5%), hits no more rapids into the stock and takes no longer (unless
// --load-feeds lowered a feed to keep a cut within the spindle's rating: then it says so).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "cli_support.hpp"
#include "command_registry.hpp"
#include "estimate_settings.hpp"
#include "ncjoule/diagnostic.hpp"
#include "ncjoule/estimate.hpp"
#include "ncjoule/optimize.hpp"
#include "ncjoule/report.hpp"
#include "output_file.hpp"
#include "platform.hpp"
#include "progress.hpp"

namespace ncjoule::cli {
namespace {

struct OptimizeCliOptions {
  std::string file;
  std::string output;
  bool in_place = false;
  bool no_air_feeds = false;
  bool no_rapid_links = false;
  bool load_feeds = false;
  double load_share_pct = 70;
  double max_feed_factor = 1.3;
  double min_feed_factor = 0.25;
  double finish_depth_mm = 0.5;
  double margin_mm = 1.0;
  double air_feed_mm_min = 0;
  bool json = false;
  EstimateSettings settings;
};

// Rapids that cut the stock, as removal warns of them.
std::size_t collisions(const Estimate& e) {
  return std::size_t(std::count_if(e.diagnostics.begin(), e.diagnostics.end(), [](const auto& d) {
    return d.message.size() >= 11 &&
           d.message.compare(d.message.size() - 11, 11, "(collision)") == 0;
  }));
}

bool same_file(const std::string& a, const std::string& b) {
  std::error_code ec;
  return a == b || std::filesystem::equivalent(a, b, ec);
}

// Why the program cannot be optimized with what is known of it; empty when it can.
std::string refusal(const Estimate& e, const EstimateOptions& options) {
  if (!e.removal) return "optimize needs the material removal simulation (leave out --no-removal)";
  for (const SetupSummary& s : e.setups)
    if (s.stock_source == StockSource::Guessed || s.stock_from == "guess")
      return "its stock is guessed from its cuts (" + s.stock +
             "): what runs clear of a guess need not be clear of the real stock. Give the stock "
             "(--stock box:XMIN,YMIN,ZMIN,XMAX,YMAX,ZMAX, a job file's stock, a .stock file next "
             "to the program) or post it from the CAM with its stock (docs/stock.md)";
  if (e.setups.size() != 1)
    return "it has " + std::to_string(e.setups.size()) +
           " setups; optimize handles programs of one setup";
  if (e.removal->z_mirrored) return "its Z is read mirrored (+Z into the work)";
  if (options.stock && options.stock->kind == StockSpec::Kind::Stl)
    return "its stock is an STL solid; optimize takes a box stock";
  if (e.removal->engine != EngineKind::Dexel)
    return "optimize replays the program on the dexel engine (leave out --engine voxel)";
  return {};
}

std::string money(double value, const std::string& currency) {
  char text[64];
  std::snprintf(text, sizeof text, "%.4f %s", value, currency.c_str());
  return text;
}

void print_savings(const Estimate& before, const Estimate& after, const OptimizePlan& plan,
                   const OptimizedText& written, const std::string& output, std::FILE* out) {
  std::size_t air = 0, rapid = 0, load = 0;
  for (const BlockEdit& e : plan.edits) {
    if (e.rule == EditRule::AirFeed) ++air;
    if (e.rule == EditRule::RapidLink) ++rapid;
    if (e.rule == EditRule::LoadFeed) ++load;
  }
  const ProgramTotals a = program_totals(before), b = program_totals(after);
  std::fprintf(out,
               "%s: %zu blocks changed (%zu air feeds, %zu rapids, %zu load feeds), %zu restore "
               "blocks added; wrote %s\n",
               printable(before.file).c_str(), written.changed_blocks, air, rapid, load,
               written.restore_blocks, printable(output).c_str());
  std::fprintf(out,
               "  %zu feed moves, %zu clear of the stock by the tool radius plus %.2f mm, %zu of "
               "them in blocks that may change\n",
               plan.feed_moves, plan.clear_moves, plan.margin_mm, plan.simple_clear_moves);
  if (load || plan.finishing_passes)
    std::fprintf(out,
                 "  load feeds: %zu lowered and %zu raised to keep the predicted cutting power "
                 "within %.0f%% of the spindle's rating (at most %.2f times the programmed feed); "
                 "%zu finishing passes (under %.2f mm deep or wide) left as they were\n",
                 plan.load_lowered, plan.load_raised, 100 * plan.load_share, plan.max_feed_factor,
                 plan.finishing_passes, plan.finish_depth_mm);
  if (after.time_s > before.time_s)
    std::fprintf(
        out,
        "  the time grew by %.1f s: %zu cutting feeds were lowered to keep their predicted "
        "cutting power within %.0f%% of the spindle's rating\n",
        after.time_s - before.time_s, plan.load_lowered, 100 * plan.load_share);
  if (plan.too_long)
    std::fprintf(out, "  %zu left as they were: the marked block would pass the line length\n",
                 plan.too_long);
  const std::string currency = printable(a.currency);
  std::fprintf(out, "\n  %-10s %14s %14s %14s\n", "", "original", "optimized", "saved");
  auto row = [out](const char* name, double x, double y, const char* unit, int decimals) {
    const double pct = x != 0 ? 100 * (x - y) / x : 0;
    std::fprintf(out, "  %-10s %11.*f %-2s %11.*f %-2s %11.*f %-2s (%.1f%%)\n", name, decimals, x,
                 unit, decimals, y, unit, decimals, x - y, unit, pct);
  };
  row("time", a.time_s, b.time_s, "s", 1);
  row("air cut", a.air_cut_s, b.air_cut_s, "s", 1);
  row("energy", a.energy_j / 1000, b.energy_j / 1000, "kJ", 2);
  std::fprintf(out, "  %-10s %14s %14s %14s\n", "cost", money(a.cost, currency).c_str(),
               money(b.cost, currency).c_str(), money(a.cost - b.cost, currency).c_str());
  std::fprintf(out, "  %-10s %11.0f mm3 %9.0f mm3 %+10.3f%%\n", "removed", a.removed_mm3,
               b.removed_mm3,
               a.removed_mm3 > 0 ? 100 * (b.removed_mm3 - a.removed_mm3) / a.removed_mm3 : 0.0);
  // By operation, as compare explains a difference: what the original takes more than the
  // optimized program, in time, energy and cost.
  std::vector<RankedProgram> ranked = rank_programs({b, a}, RankBy::Time);
  const RankedProgram* best = &ranked[0];
  const RankedProgram* other = &ranked[1];
  if (best->totals.file != b.file) std::swap(best, other);
  for (const RankBy by : {RankBy::Time, RankBy::Energy, RankBy::Cost}) {
    const std::string ops = explain_by_operation(*other, *best, by);
    std::fprintf(out, "\n  saved by operation (%s): %s", std::string(rank_by_name(by)).c_str(),
                 ops.empty() ? "none" : printable(ops).c_str());
  }
  std::fprintf(out, "\n\nreview with: ncjoule compare %s %s\n", printable(before.file).c_str(),
               printable(output).c_str());
}

int run_optimize(const OptimizeCliOptions& o) {
  if (o.in_place) {
    std::cerr << "ncjoule optimize: --in-place is refused: the original is never changed; give "
                 "the optimized program's name with -o OUT\n";
    return kUsage;
  }
  if (o.output.empty() || o.output == "-") {
    std::cerr << "ncjoule optimize: give the optimized program's file with -o OUT\n";
    return kUsage;
  }
  if (o.file == "-" || same_file(o.file, o.output)) {
    std::cerr << "ncjoule optimize: -o must name a file other than the program (the original is "
                 "never changed)\n";
    return kUsage;
  }
  int status = kOk;
  MachineProfile machine;
  if (!load_machine(o.settings, machine, o.file)) return kInputError;
  const std::optional<EstimateOptions> options =
      estimate_options(o.settings, o.file, machine, status);
  if (!options) return status;
  if (o.load_feeds && !(machine.power.spindle_rated_w > 0) &&
      machine.power.spindle_power_curve.empty()) {
    std::cerr << "ncjoule optimize: --load-feeds needs the spindle's rating: the machine profile "
                 "gives no spindle_rated_w (docs/machine-profiles.md)\n";
    return kInputError;
  }
  if (o.load_feeds && machine.power.placeholder_spindle)
    std::cerr << "ncjoule optimize: warning: the load target is a share of a spindle rating that "
              << kPlaceholderSpindleAdvice << "\n";
  const auto input =
      read_source(o.file, input_limit_bytes(o.settings), memory_budget_bytes(o.settings));
  if (!input) return kInputError;

  ProgressBar progress("estimating", 2);
  progress.begin(0, input->path);
  EstimateOptions first = *options;
  first.progress = progress.callback();
  std::vector<CanonCommand> commands;
  first.keep_commands = &commands;
  const Estimate before = estimate_program(*input, machine, first);
  print_diagnostics(before.diagnostics, before.diagnostics_dropped);
  if (before.failed) {
    progress.finish();
    std::cerr << "ncjoule: " << printable(input->path)
              << " could not be estimated (see above); nothing was written\n";
    return kInputError;
  }
  if (const std::string why = refusal(before, *options); !why.empty()) {
    progress.finish();
    std::cerr << "ncjoule optimize: " << printable(input->path)
              << " is not optimized: " << printable(why) << "; nothing was written\n";
    return kInputError;
  }

  OptimizeOptions rules;
  rules.air_feeds = !o.no_air_feeds;
  rules.rapid_links = !o.no_rapid_links;
  rules.margin_mm = o.margin_mm;
  rules.air_feed_mm_min = o.air_feed_mm_min;
  rules.load_feeds = o.load_feeds;
  rules.load_share = o.load_share_pct / 100;
  rules.max_feed_factor = o.max_feed_factor;
  rules.min_feed_factor = o.min_feed_factor;
  rules.finish_depth_mm = o.finish_depth_mm;
  // Rule c starts from each line's predicted load at its programmed feed.
  const std::unique_ptr<OptimizeStart> start =
      optimize_start(*input, before, commands, machine.kinematics);
  const std::map<int, double>& rpm = start->rpm_by_line;
  EstimateOptions second = *options;
  second.progress = progress.callback();
  if (!second.dialect)
    second.dialect_choice =
        DialectChoice{before.dialect, before.dialect_origin, before.dialect_reason};
  // The written text estimated as the check needs it; rule c asks it for the loads it predicts.
  std::optional<Estimate> after;
  std::string after_text;
  auto estimate_written = [&](const OptimizedText& text) {
    progress.begin(1, o.output);
    after = estimate_program(make_source(o.output, text.text), machine, second);
    after_text = text.text;
  };
  const LoadsOf loads_of = [&](const OptimizedText& text) {
    estimate_written(text);
    return mean_spindle_loads(*after, rpm, &text.original_line);
  };
  const LoadedPlan loaded = plan_with_load_feeds(start->input, rules, loads_of);
  const OptimizePlan& plan = loaded.plan;
  const OptimizedText& written = loaded.text;
  commands.clear();
  commands.shrink_to_fit();
  if (written.changed_blocks == 0) {
    progress.finish();
    if (o.json) {
      std::printf("{\"changed_blocks\": 0, \"feed_moves\": %zu, \"clear_moves\": %zu, "
                  "\"simple_clear_moves\": %zu}\n",
                  plan.feed_moves, plan.clear_moves, plan.simple_clear_moves);
      return kOk;
    }
    std::printf("%s: no block to change (%zu feed moves, %zu clear of the stock by the margin, "
                "%zu of them in blocks that may change); nothing was written\n",
                printable(input->path).c_str(), plan.feed_moves, plan.clear_moves,
                plan.simple_clear_moves);
    return kOk;
  }

  // The proof before anything is written: the optimized text, estimated with the same stock.
  if (!after || after_text != written.text) estimate_written(written);
  progress.finish();
  std::vector<std::string> failed;
  if (after->failed || !after->removal) {
    failed.push_back("the optimized program could not be estimated");
  } else {
    const double v0 = before.removal->removed_mm3, v1 = after->removal->removed_mm3;
    if (std::abs(v1 - v0) > 0.005 * std::max(v0, 1e-9)) {
      char text[160];
      std::snprintf(text, sizeof text,
                    "it removes %.1f mm3 where the original removes %.1f mm3 (more than 0.5%% "
                    "apart)",
                    v1, v0);
      failed.push_back(text);
    }
    if (collisions(*after) > collisions(before))
      failed.push_back("it has " + std::to_string(collisions(*after)) +
                       " rapids into the stock where the original has " +
                       std::to_string(collisions(before)));
    // A load feed lowered to keep a cut within the rating may make the program longer: the
    // output says so.
    if (after->time_s > before.time_s && plan.load_lowered == 0)
      failed.push_back("it takes longer than the original");
    if (refusal(*after, second).size()) failed.push_back("its stock is not the original's");
  }
  if (!failed.empty()) {
    std::cerr << "ncjoule optimize: the optimized program failed its checks, nothing was "
                 "written:";
    for (const std::string& why : failed)
      std::cerr << "\n  " << printable(why);
    std::cerr << '\n';
    return kOutputError;
  }
  // What it says goes to standard error when the program itself goes to standard output.
  std::FILE* const out = platform::is_standard_output(o.output) ? stderr : stdout;
  if (const int w = write_program(o.file, o.output, nullptr, written.text); w != kOk) return w;
  if (o.json) {
    // What changed and what the checks saw, then the two programs as compare --json gives them.
    std::vector<RankedProgram> ranked =
        rank_programs({program_totals(before), program_totals(*after)}, RankBy::Time);
    std::size_t air = 0, load = 0;
    for (const BlockEdit& e : plan.edits) {
      air += e.rule == EditRule::AirFeed;
      load += e.rule == EditRule::LoadFeed;
    }
    std::fprintf(out,
                 "{\"changed_blocks\": %zu, \"air_feeds\": %zu, \"rapids\": %zu, "
                 "\"restore_blocks\": %zu, \"feed_moves\": %zu, \"clear_moves\": %zu, "
                 "\"margin_mm\": %.6g, \"removed_mm3\": [%.6f, %.6f], \"time_s\": [%.6f, %.6f], "
                 "\"collisions\": [%zu, %zu],\n",
                 written.changed_blocks, air, written.changed_blocks - air - load,
                 written.restore_blocks, plan.feed_moves, plan.clear_moves, plan.margin_mm,
                 before.removal->removed_mm3, after->removal->removed_mm3, before.time_s,
                 after->time_s, collisions(before), collisions(*after));
    if (o.load_feeds)
      std::fprintf(out,
                   " \"load_feeds\": {\"lowered\": %zu, \"raised\": %zu, \"finishing_passes\": "
                   "%zu, \"share\": %.6g, \"max_feed_factor\": %.6g, \"finish_depth_mm\": %.6g, "
                   "\"passes\": %d, \"over_share\": %zu, \"min_feed_factor\": %.6g, "
                   "\"floored\": %zu},\n",
                   plan.load_lowered, plan.load_raised, plan.finishing_passes, plan.load_share,
                   plan.max_feed_factor, plan.finish_depth_mm, loaded.passes, loaded.over_share,
                   plan.min_feed_factor, plan.load_floored);
    std::fprintf(out, " \"comparison\": ");
    std::fputs((comparison_json(ranked, machine, 1, RankBy::Time) + "}\n").c_str(), out);
  } else {
    print_savings(before, *after, plan, written, o.output, out);
    if (loaded.over_share)
      std::fprintf(out,
                   "  %zu load-scaled blocks are still predicted above the share after %d passes "
                   "(%zu held at %.2f times their programmed feed)\n",
                   loaded.over_share, loaded.passes, plan.load_floored, plan.min_feed_factor);
  }
  std::fflush(out);
  return kOk;
}

const Registration registration([](CLI::App& app, int& exit_code) {
  auto options = std::make_shared<OptimizeCliOptions>();
  CLI::App* cmd = app.add_subcommand(
      "optimize", "Write a faster alternative of a program with a known stock: feed moves clear "
                  "of the in-process stock at the air feed, clear retracts and links as rapids; "
                  "nothing that cuts changes (docs/optimize.md)");
  cmd->add_option("file", options->file, "NC program")->required();
  cmd->add_option("-o,--output", options->output, "The optimized program (a new file)");
  cmd->add_flag("-i,--in-place", options->in_place, "Refused: the original is never changed");
  add_estimate_settings(*cmd, options->settings);
  cmd->add_flag("--no-air-feeds", options->no_air_feeds,
                "Leave the feed of clear feed moves as it is");
  cmd->add_flag("--no-rapid-links", options->no_rapid_links,
                "Leave clear retracts and links as feed moves");
  cmd->add_flag("--load-feeds", options->load_feeds,
                "Scale the feeds of cutting blocks so their predicted cutting power stays within "
                "--load-share of the spindle's rating (off by default)");
  cmd->add_option("--load-share", options->load_share_pct,
                  "With --load-feeds: the load target, percent of the spindle's rating (default "
                  "70)")
      ->check(CLI::Range(1.0, 100.0));
  cmd->add_option("--max-feed-factor", options->max_feed_factor,
                  "With --load-feeds: a raised feed stays at most this times the programmed one "
                  "(default 1.3; 1: only lower)")
      ->check(CLI::Range(1.0, 10.0));
  cmd->add_option("--min-feed-factor", options->min_feed_factor,
                  "With --load-feeds: a lowered feed stays at least this times the programmed "
                  "one (default 0.25)")
      ->check(CLI::Range(0.01, 1.0));
  cmd->add_option("--finish-depth", options->finish_depth_mm,
                  "With --load-feeds: cuts shallower or narrower than this (mm) are finishing "
                  "passes, never changed (default 0.5)")
      ->check(CLI::Range(0.0, 1000.0));
  cmd->add_option("--margin", options->margin_mm,
                  "Clearance beyond the tool's radius and below its tip, mm (default 1; at least "
                  "two grid cells)")
      ->check(CLI::Range(0.0, 1000.0));
  cmd->add_option("--air-feed", options->air_feed_mm_min,
                  "Air feed, mm/min (default: the profile's air_feed_mm_min, else the machine's "
                  "highest feed); capped by each axis's max_feed")
      ->check(CLI::Range(0.0, 1e6));
  cmd->add_flag("--json", options->json,
                "Print what changed and what the checks saw as JSON, with the two programs as "
                "compare --json gives them (docs/optimize.md)");
  cmd->footer("Exit codes: 0 written, or nothing to change; 1 bad command line (--in-place, no "
              "-o, -o naming the program); 2 the program cannot be read or estimated, or cannot "
              "be optimized (a guessed stock, several setups); 3 nothing was written: the "
              "optimized program failed its checks or could not be written.");
  cmd->callback([options, &exit_code] { exit_code = run_optimize(*options); });
});

} // namespace
} // namespace ncjoule::cli
