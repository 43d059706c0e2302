// fenestra: command-line front end over the core library.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <iostream>
#include <map>
#include <new>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "annual/annual_contributions.h"
#include "annual/annual_cut_study.h"
#include "annual/annual_study.h"
#include "cluster_handoff.h"
#include "format/atomic_file.h"
#include "format/image_writer.h"
#include "format/output_pair.h"
#include "io/annual_result.h"
#include "io/results.h"
#include "io/sky_output.h"
#include "io/solve_result.h"
#include "scene/input_limits.h"
#include "scene/scene.h"
#include "solve/goals.h"
#include "solve/prediction_check.h"
#include "solve/solver.h"
#include "study/cost_model.h"
#include "study/setup_checks.h"
#include "trace/contributions.h"
#include "trace/evaluate.h"
#include "util/byte_size.h"
#include "util/out_of_memory.h"
#include "util/wording.h"

namespace {

const char* kUsage = R"(usage:
  fenestra contributions SCENE.json -o OUT[.npz] [options]
      One pass of paths per sensor: the contribution matrix E of every opening element, the
      error-compensation buffers A and T, all-closed and all-open values, with standard errors.
      Writes OUT.npz (NumPy arrays) and OUT.json (summary listing every element).
  fenestra evaluate SCENE.json --openings OPENINGS.json -o OUT.json [options]
      Path-traces the scene with the given openings really cut; per-sensor value and standard error.
  fenestra solve SCENE.json -o RESULT.json [options]
      Contributions, then the opening solver (NNLS start, genetic algorithm, exact re-ranking):
      writes the openings (rectangles, readable by evaluate --openings), predicted values, errors,
      timings and the genetic history. Settings from the scene's "goals" and "solver" sections.
      With a "climate" sky, goals.climate asks for sDA, ASE, EN 17037, UDI or an annual mean (and
      goals.least_glazing for the least glass): each goal's figure is printed, from the path records
      and with real cutters, and written under "climate". See docs/solver.md, "Climate goals".
  fenestra annual SCENE.json --openings OPENINGS.json -o OUT[.npz] [--cutters] [options]
      A scene whose sky is "climate" (a weather file): one pass of paths per sensor, then every
      sensor's illuminance at every hour of the year with the openings open, its direct-sun part,
      and the climate-based metrics (DA, cDA, UDI, sDA, ASE, EN 17037). Writes OUT.npz (arrays,
      lux) and OUT.json (space and per-sensor metrics). With --cutters the paths are traced with
      the openings really cut (no records: the ground truth, and edges anywhere in thick walls).
      See docs/annual.md.
  fenestra sky SCENE.json -o SKY.exr [--json SUMMARY.json]
      Writes the scene's sky as an equirectangular map (.exr or .hdr, cd/m^2, Blender's convention;
      other formats cannot keep the values and are refused) and prints the horizontal illuminances
      and the sun list (also as JSON with --json).

options:
  --paths N     paths per sensor, 1 to 1073741824 (overrides render.paths_per_sensor)
  --seed N      random seed, 0 to 9007199254740992 (overrides render.seed)
  --threads N   worker threads, 0 to 4096, 0 = all (overrides render.threads)
  --max-memory SIZE  memory the run may use, e.g. 8G, 512M or bytes (default: what the system
                has available, within ulimit -v); runs that would need more are refused
  --json PATH   (sky) also write the summary as JSON
  --cutters     (annual) trace the paths with the openings really cut
  --strict      the setup checks' warnings are errors (status 1, nothing written): goals all 0,
                sensors outdoors or facing down, a room open to the sky, domain panels seen
                from the side the solver does not take for the room (docs/outputs.md)
  --quiet       no progress on stderr
  -h, --help    this text

on a Dask cluster (solve, contributions, evaluate and annual sharded by sensors; sky built on a
worker; docs/distributed.md), with results equal bit for bit to a single process's:
  --workers N          start a local cluster of N worker processes
  --scheduler ADDRESS  use a running Dask scheduler, e.g. tcp://host:8786
  --shards N           blocks of sensors (default: one per worker; not for sky)

Values are luminance-weighted irradiance: lux when the sky is given in cd/m^2.
Outputs are checked before the run (never an input, a symbolic link or a device) and written whole
or not at all. Exit status: 0 done, 1 error, 2 usage error, 130 / 143 interrupted by SIGINT /
SIGTERM (nothing written).
)";

struct Args {
  std::string command, scene, output, openings, summary;
  std::map<std::string, long long> overrides;
  bool quiet = false;
  bool cutters = false;
  bool strict = false;
  uint64_t max_memory = 0;  // bytes; 0: detected (util/memory_limit.h)
};

[[noreturn]] void usage_error(const std::string& message) {
  std::cerr << "fenestra: " << message << "\n\n" << kUsage;
  std::exit(2);
}

// The same ranges as the scene file's keys (scene/input_limits.h), checked before any conversion.
long long parse_integer(const std::string& flag, const std::string& text, const fenestra::IntegerRange& range) {
  const std::string expected = flag + " expects an integer from " + std::to_string(range.lo) + " to " +
                               std::to_string(range.hi) + " (as " + range.key + "), got '" + text + "'";
  long long v = 0;
  try {
    size_t used = 0;
    v = std::stoll(text, &used);
    if (used != text.size() || text.find_first_not_of("0123456789") != std::string::npos)
      throw std::invalid_argument("");
  } catch (const std::exception&) {
    usage_error(expected);
  }
  if (!range.contains(v)) usage_error(expected);
  return v;
}

Args parse_args(int argc, char** argv) {
  Args a;
  std::vector<std::string> positional;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) usage_error(arg + " needs a value");
      return argv[++i];
    };
    if (arg == "-h" || arg == "--help") {
      std::cout << kUsage;
      std::exit(0);
    } else if (arg == "-o" || arg == "--output") {
      a.output = value();
    } else if (arg == "--openings") {
      a.openings = value();
    } else if (arg == "--json") {
      a.summary = value();
    } else if (arg == "--paths" || arg == "--seed" || arg == "--threads") {
      a.overrides[arg] = parse_integer(arg, value(),
                                       arg == "--paths"  ? fenestra::limits::kPathsPerSensor
                                       : arg == "--seed" ? fenestra::limits::kSeed
                                                         : fenestra::limits::kThreads);
    } else if (arg == "--max-memory") {
      try {
        a.max_memory = fenestra::parse_byte_size(value(), "--max-memory");
      } catch (const std::invalid_argument& e) {
        usage_error(e.what());
      }
    } else if (arg == "--quiet") {
      a.quiet = true;
    } else if (arg == "--cutters") {
      a.cutters = true;
    } else if (arg == "--strict") {
      a.strict = true;
    } else if (!arg.empty() && arg[0] == '-') {
      usage_error("unknown option '" + arg + "'");
    } else {
      positional.push_back(arg);
    }
  }
  if (positional.empty()) usage_error("no command given");
  a.command = positional[0];
  if (a.command != "contributions" && a.command != "evaluate" && a.command != "sky" && a.command != "solve" &&
      a.command != "annual")
    usage_error("unknown command '" + a.command + "'");
  if (positional.size() != 2) usage_error(a.command + " takes exactly one scene file");
  a.scene = positional[1];
  if (a.output.empty()) usage_error(a.command + " needs -o OUT");
  if ((a.command == "evaluate" || a.command == "annual") && a.openings.empty())
    usage_error(a.command + " needs --openings OPENINGS.json");
  if (a.command != "sky" && !a.summary.empty()) usage_error("--json belongs to the sky command");
  if (a.command != "annual" && a.cutters) usage_error("--cutters belongs to the annual command");
  if (a.command == "sky" && a.strict) usage_error("--strict belongs to solve, contributions, evaluate and annual");
  return a;
}

// Prints the progress fraction on stderr about once a second while `work` runs.
template <typename F>
auto with_progress(fenestra::Progress& progress, bool quiet, F work) {
  std::atomic<bool> done{false};
  std::thread reporter([&] {
    int ticks = 0;
    while (!done) {
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
      if (!quiet && ++ticks % 10 == 0)
        std::fprintf(stderr, "  %s: %3.0f%%\n", progress.status().c_str(), 100.0 * progress.fraction());
    }
  });
  try {
    auto result = work();
    done = true;
    reporter.join();
    return result;
  } catch (...) {
    done = true;
    reporter.join();
    throw;
  }
}

// What the program is doing, for an out-of-memory message.
std::string g_stage = "starting";

// SIGINT and SIGTERM cancel the run through the Progress flag (an atomic store: async-signal-
// safe); the run unwinds, its unfinished outputs vanish and the exit status is 128 + the signal.
// A second signal terminates at once (SA_RESETHAND); outputs still appear whole or not at all.
fenestra::Progress g_progress;
volatile std::sig_atomic_t g_signal = 0;
static_assert(std::atomic<bool>::is_always_lock_free, "the cancel flag must be safe to set in a signal handler");

void on_signal(int sig) {
  g_signal = sig;
  g_progress.cancel();
}

void install_signal_handlers() {
  struct sigaction action {};
  action.sa_handler = on_signal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESETHAND;
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
  fenestra::set_write_interrupt(&g_progress);  // no output is renamed into place after a signal
}

// Every file the command writes, in the order written.
std::vector<std::string> output_paths(const Args& a) {
  if (a.command == "contributions" || a.command == "annual") {  // as write_contributions / write_annual name them
    const auto [npz, json] = fenestra::npz_json_pair(a.output);
    return {npz, json};
  }
  if (!a.summary.empty()) return {a.output, a.summary};
  return {a.output};
}

// Each climate goal: required, reached (path records) and checked (real cutters), and the glazing.
void print_climate_summary(const fenestra::Scene& scene, const fenestra::SolveResult& r) {
  using namespace fenestra;
  if (!r.climate.active) return;
  const auto text = [](const ClimateGoal& g, double x) {
    char s[32];
    if (g.unit() == "lux") std::snprintf(s, sizeof s, "%.0f lx", x);
    else std::snprintf(s, sizeof s, "%.1f %%", 100.0 * x);
    return std::string(s);
  };
  const ClimateOutcome& c = r.climate;
  for (size_t g = 0; g < scene.sensors.climate_goals.goals.size(); ++g) {
    const ClimateGoal& goal = scene.sensors.climate_goals.goals[g];
    std::string line = "climate goal " + goal.describe() + ":";
    const auto said = [&](const std::vector<ClimateFigure>& f) {
      return text(goal, f[g].achieved) + (figure_meets(goal, f[g].achieved) ? " met" : " NOT met");
    };
    if (c.headline_cutters && g < c.verified.size()) {  // the records disagree beyond the noise
      line += " " + said(c.verified) + " with real cutters";
      if (g < c.achieved.size()) line += "; path records " + said(c.achieved);
    } else {
      if (g < c.achieved.size()) line += " " + said(c.achieved);
      if (g < c.verified.size()) line += "; real cutters " + said(c.verified);
    }
    std::printf("%s\n", line.c_str());
  }
  std::printf("glazing %.2f m2 of %.2f m2 of opening domain\n", c.glazing_area_m2, c.domain_area_m2);
}

// Each room's (sensor group's) figures of the final openings' year, and the floor's.
void print_rooms(const nlohmann::json& rooms) {
  for (const nlohmann::json& room : rooms) {
    const nlohmann::json& m = room["space"];
    std::printf("room %s (%zu sensors): sDA %.1f %%, ASE %.1f %%, mean illuminance %.0f lx\n",
                room["name"].get<std::string>().c_str(), room["sensors"].size(),
                100.0 * m["spatial_daylight_autonomy"].get<double>(), 100.0 * m["annual_sunlight_exposure"].get<double>(),
                m["mean_illuminance_lux"].get<double>());
  }
}

// What the tracer dropped (non-finite light, conditions past their limit): a warning when anything.
void warn_if_dropped(const fenestra::DropCounts& dropped) {
  const std::string w = fenestra::dropped_warning(dropped);
  if (!w.empty()) std::fprintf(stderr, "fenestra: warning: %s\n", w.c_str());
}

int run_annual(const Args& a, const fenestra::Scene& scene, fenestra::Progress& progress,
               const std::vector<std::string>& setup) {
  using namespace fenestra;
  if (!scene.climate)
    throw std::invalid_argument("scene '" + a.scene + "': annual needs a sky of type \"climate\" (a weather file; " +
                                "docs/scene-format.md)");
  if (a.cutters) {
    AnnualStudy study = with_progress(
        progress, a.quiet, [&] { return annual_study_with_cutters(scene, read_openings(a.openings, scene.site), &progress); });
    study.warnings = setup;
    const auto paths = write_annual(scene, study, a.output);
    const AnnualMetrics& m = study.metrics;
    std::printf("annual (openings cut): %zu sensors x %d hours (%d occupied), %d paths per sensor; %.2f s\n"
                "%s\nwrote %s\nwrote %s\n",
                scene.sensors.size(), m.hours, m.occupied_hours, study.paths_per_sensor, study.seconds,
                m.to_string().c_str(), paths.first.c_str(), paths.second.c_str());
    return 0;
  }
  const OpenRegion region = region_of_openings(scene, read_openings(a.openings, scene.site));  // before the long pass
  const Contributions c =
      with_progress(progress, a.quiet, [&] { return compute_contributions(scene, &progress, /*transport=*/false); });
  AnnualStudy study = with_progress(progress, a.quiet, [&] { return annual_study(scene, c, region, &progress); });
  study.warnings = setup;
  const auto paths = write_annual(scene, study, a.output);
  const AnnualMetrics& m = study.metrics;
  std::printf("annual: %zu sensors x %d hours (%d occupied), %d paths per sensor; contributions %.2f s, year %.3f s\n"
              "%s\nwrote %s\nwrote %s\n",
              c.sensor_count(), m.hours, m.occupied_hours, c.paths_per_sensor, c.seconds, study.seconds,
              m.to_string().c_str(), paths.first.c_str(), paths.second.c_str());
  warn_if_dropped(c.dropped);
  return 0;
}

int run(const Args& a) {
  using namespace fenestra;
  g_stage = "loading scene '" + a.scene + "'";
  // An annual study with the openings cut keeps no records: its paths cost what evaluate's do.
  const CostCommand cost =
      cost_command(a.command == "annual" ? (a.cutters ? "annual_cutters" : "contributions") : a.command);
  set_cost_context({a.max_memory, cost});  // the loader's cost checks see both
  // Outputs are checked before any work (docs/outputs.md): writable, regular files, not inputs.
  const std::vector<std::string> outputs = output_paths(a);
  std::vector<std::string> inputs = {a.scene};
  if (!a.openings.empty()) inputs.push_back(a.openings);
  check_output_paths(outputs, inputs);
  if (a.command == "sky") encode_image(a.output, 1, 1, 3, {0.0f, 0.0f, 0.0f});  // a format OpenImageIO writes
  Scene scene = load_scene(a.scene, &g_progress);
  check_output_paths(outputs, scene.input_files);  // its OBJ and environment map too
  g_stage = "running " + a.command + " on scene '" + a.scene + "'";
  if (a.overrides.count("--paths")) {
    if (a.overrides.at("--paths") < 1) throw std::invalid_argument("--paths must be at least 1");
    scene.render.paths_per_sensor = static_cast<int>(a.overrides.at("--paths"));
  }
  if (a.overrides.count("--seed")) scene.render.seed = static_cast<uint64_t>(a.overrides.at("--seed"));
  if (a.overrides.count("--threads")) scene.render.threads = static_cast<int>(a.overrides.at("--threads"));
  if (!a.quiet) std::fprintf(stderr, "%s\n", scene.to_string().c_str());
  for (const std::string& w : sky_warnings(scene.daylight.get())) std::fprintf(stderr, "fenestra: warning: %s\n", w.c_str());
  if (a.command == "contributions" || a.command == "evaluate") {
    const std::string dark = dark_sky_warning(*scene.sky, scene.daylight.get());  // solve refuses such a sky
    if (!dark.empty()) std::fprintf(stderr, "fenestra: warning: %s\n", dark.c_str());
  }

  if (a.command == "solve") {  // the solver's own paths and seed
    if (a.overrides.count("--paths")) scene.solver.paths_per_sensor = scene.render.paths_per_sensor;
    if (a.overrides.count("--seed")) scene.solver.seed = scene.render.seed;
  }
  check_cost(scene, cost);  // memory and time, before any work (docs/cost.md)
  if (a.command == "solve") require_goals(scene);  // before any tracing
  // The setup checks (docs/outputs.md): warnings on stderr and in the output's "warnings", or
  // with --strict an error before any work.
  std::vector<std::string> setup;
  if (a.command != "sky") {
    const SetupStage stage = a.command == "solve"           ? SetupStage::Solve
                             : a.command == "contributions" ? SetupStage::Contributions
                                                            : SetupStage::Evaluate;
    setup = setup_messages(scene, check_setup(scene, stage), a.strict);
    for (const std::string& w : setup) std::fprintf(stderr, "fenestra: warning: %s\n", w.c_str());
  }
  if (a.command == "sky") {
    const nlohmann::json summary = sky_summary(scene);
    const SkyImage image = sky_image(*scene.sky, scene.daylight.get());
    std::vector<float> flat;
    flat.reserve(image.pixels.size() * 3);
    for (const Rgb& p : image.pixels) flat.insert(flat.end(), {p[0], p[1], p[2]});
    const std::string bytes = encode_image(a.output, image.width, image.height, 3, flat);
    // The map and the summary appear together or not at all.
    std::vector<OutputFile> files = {
        {a.output, [&](std::ostream& o) { o.write(bytes.data(), static_cast<std::streamsize>(bytes.size())); }}};
    if (!a.summary.empty())
      files.push_back({a.summary, [&](std::ostream& o) {
                         o << summary.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) << "\n";
                       }});
    write_files_atomically(files, scene.input_files);
    std::printf("%swrote %s\n", sky_report(summary).c_str(), a.output.c_str());
    if (!a.summary.empty()) std::printf("wrote %s\n", a.summary.c_str());
    return 0;
  }
  Progress& progress = g_progress;
  if (a.command == "solve") {
    if (!a.quiet)
      std::fprintf(stderr, "estimated memory: %s\n", memory_summary(scene, CostCommand::Solve, memory_limit()).c_str());
    SolveResult r = with_progress(progress, a.quiet, [&] { return solve_openings(scene, &progress); });
    const std::vector<std::string> own = r.warnings;  // the solver's (the setup's are printed above)
    r.warnings.insert(r.warnings.begin(), setup.begin(), setup.end());
    const nlohmann::json result = solve_result_json(scene, r);
    write_json(a.output, result);
    double total = 0.0;
    for (const auto& t : r.timings) total = t.stage == "total" ? t.seconds : total;
    if (r.climate.active)  // its per-sensor errors measure how the openings follow the element answer's light
      std::printf("solve: %s, %s; %.2f s\nwrote %s\n", counted(r.openings.size(), "opening").c_str(),
                  counted(static_cast<size_t>(std::count(r.open.begin(), r.open.end(), 1)), "open element").c_str(),
                  total, a.output.c_str());
    else
      std::printf("solve: %s, %s; relative RMS error %.2f%% (linear model %.2f%%, "
                  "compensated %.2f%%), worst sensor %.1f%%; %.2f s\nwrote %s\n",
                  counted(r.openings.size(), "opening").c_str(),
                  counted(static_cast<size_t>(std::count(r.open.begin(), r.open.end(), 1)), "open element").c_str(),
                  100 * r.error.relative_rms, 100 * r.linear_error.relative_rms, 100 * r.compensated_error.relative_rms,
                  100 * r.error.max_relative, total, a.output.c_str());
    if (r.verified && !r.climate.active)
      std::printf("checked with real cutters: relative RMS error %.2f%%, worst sensor %.1f%%\n",
                  100 * r.verified_error.relative_rms, 100 * r.verified_error.max_relative);
    print_climate_summary(scene, r);
    if (r.climate.active) print_rooms(result["climate"]["rooms"]);
    for (const std::string& w : own) std::fprintf(stderr, "fenestra: warning: %s\n", w.c_str());  // with any drop
    return 0;
  }
  if (a.command == "contributions") {
    if (!a.quiet)
      std::fprintf(stderr, "estimated memory: %s\n",
                   memory_summary(scene, CostCommand::Contributions, memory_limit()).c_str());
    Contributions c = with_progress(progress, a.quiet, [&] { return compute_contributions(scene, &progress); });
    c.warnings = setup;
    const auto paths = write_contributions(scene, c, a.output);
    std::printf("contributions: %zu sensors x %zu elements, %d paths per sensor, %.2f s\n", c.sensor_count(),
                c.element_count(), c.paths_per_sensor, c.seconds);
    std::printf("wrote %s\nwrote %s\n", paths.first.c_str(), paths.second.c_str());
    const std::string sparse = sparse_sampling_warning(c.paths_per_sensor, c.element_count());
    if (!sparse.empty()) std::fprintf(stderr, "fenestra: warning: %s\n", sparse.c_str());
    warn_if_dropped(c.dropped);
    return 0;
  }
  if (a.command == "annual") return run_annual(a, scene, progress, setup);
  const auto openings = read_openings(a.openings, scene.site);
  const auto start = std::chrono::steady_clock::now();
  const SensorValues v = with_progress(progress, a.quiet, [&] { return evaluate_openings(scene, openings, &progress); });
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  write_json(a.output, evaluation_json(v, openings.size(), scene.render.paths_per_sensor,
                                       unobstructed_horizontal_illuminance(*scene.sky, scene.suns, scene.daylight.get()), setup));
  std::printf("evaluate: %s, %s, %.2f s\nwrote %s\n", counted(scene.sensors.size(), "sensor").c_str(),
              counted(openings.size(), "opening").c_str(), seconds, a.output.c_str());
  return 0;
}

}  // namespace

static const char* signal_name(int sig) {
  return sig == SIGINT ? "SIGINT" : sig == SIGTERM ? "SIGTERM" : "a signal";
}

int main(int argc, char** argv) {
  if (fenestra::wants_cluster(argc, argv)) return fenestra::hand_to_cluster(argc, argv);
  const Args args = parse_args(argc, argv);
  install_signal_handlers();
  try {
    const int status = run(args);
    if (g_signal) {  // after the outputs were renamed into place: they are complete
      std::fprintf(stderr, "fenestra: interrupted by %s after writing its output\n", signal_name(g_signal));
      return 128 + g_signal;
    }
    return status;
  } catch (const fenestra::Cancelled&) {
    std::fprintf(stderr, "fenestra: interrupted by %s; no output written\n", signal_name(g_signal));
    return g_signal ? 128 + g_signal : 1;
  } catch (const fenestra::OutOfMemory& e) {  // what was being read or done
    std::fprintf(stderr, "fenestra: error: %s\n", e.what());
    return 1;
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr,
                 "fenestra: error: out of memory while %s: lower render.paths_per_sensor (--paths), the number of "
                 "sensors or elements (a larger opening_domain.element_size), or the sky's resolution\n",
                 g_stage.c_str());
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "fenestra: error: %s\n", e.what());
    return g_signal ? 128 + g_signal : 1;
  }
}
