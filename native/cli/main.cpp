// fenestra: command-line front end over the core library.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <map>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "io/results.h"
#include "io/sky_output.h"
#include "io/solve_result.h"
#include "solve/solver.h"
#include "scene/scene.h"
#include "trace/contributions.h"
#include "trace/evaluate.h"

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
  fenestra sky SCENE.json -o SKY.exr [--json SUMMARY.json]
      Writes the scene's sky as an equirectangular map (.exr or .hdr, cd/m^2, Blender's convention)
      and prints the horizontal illuminances and the sun list (also as JSON with --json).

options:
  --paths N     paths per sensor (overrides render.paths_per_sensor)
  --seed N      random seed (overrides render.seed)
  --threads N   worker threads, 0 = all (overrides render.threads)
  --json PATH   (sky) also write the summary as JSON
  --quiet       no progress on stderr
  -h, --help    this text

Values are luminance-weighted irradiance: lux when the sky is given in cd/m^2.
)";

struct Args {
  std::string command, scene, output, openings, summary;
  std::map<std::string, long long> overrides;
  bool quiet = false;
};

[[noreturn]] void usage_error(const std::string& message) {
  std::cerr << "fenestra: " << message << "\n\n" << kUsage;
  std::exit(2);
}

long long parse_integer(const std::string& flag, const std::string& text) {
  try {
    size_t used = 0;
    const long long v = std::stoll(text, &used);
    if (used != text.size() || v < 0) throw std::invalid_argument("");
    return v;
  } catch (const std::exception&) {
    usage_error(flag + " expects a non-negative integer, got '" + text + "'");
  }
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
      a.overrides[arg] = parse_integer(arg, value());
    } else if (arg == "--quiet") {
      a.quiet = true;
    } else if (!arg.empty() && arg[0] == '-') {
      usage_error("unknown option '" + arg + "'");
    } else {
      positional.push_back(arg);
    }
  }
  if (positional.empty()) usage_error("no command given");
  a.command = positional[0];
  if (a.command != "contributions" && a.command != "evaluate" && a.command != "sky" &&
      a.command != "solve") usage_error("unknown command '" + a.command + "'");
  if (positional.size() != 2) usage_error(a.command + " takes exactly one scene file");
  a.scene = positional[1];
  if (a.output.empty()) usage_error(a.command + " needs -o OUT");
  if (a.command == "evaluate" && a.openings.empty()) usage_error("evaluate needs --openings OPENINGS.json");
  if (a.command != "sky" && !a.summary.empty()) usage_error("--json belongs to the sky command");
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

int run(const Args& a) {
  using namespace fenestra;
  Scene scene = load_scene(a.scene);
  if (a.overrides.count("--paths")) {
    if (a.overrides.at("--paths") < 1) throw std::invalid_argument("--paths must be at least 1");
    scene.render.paths_per_sensor = static_cast<int>(a.overrides.at("--paths"));
  }
  if (a.overrides.count("--seed")) scene.render.seed = static_cast<uint64_t>(a.overrides.at("--seed"));
  if (a.overrides.count("--threads")) scene.render.threads = static_cast<int>(a.overrides.at("--threads"));
  if (!a.quiet) std::fprintf(stderr, "%s\n", scene.to_string().c_str());

  if (a.command == "sky") {
    const nlohmann::json summary = sky_summary(scene);
    write_sky_image(a.output, sky_image(scene));
    if (!a.summary.empty()) write_json(a.summary, summary);
    std::printf("%swrote %s\n", sky_report(summary).c_str(), a.output.c_str());
    if (!a.summary.empty()) std::printf("wrote %s\n", a.summary.c_str());
    return 0;
  }
  Progress progress;
  if (a.command == "solve") {
    if (a.overrides.count("--paths")) scene.solver.paths_per_sensor = scene.render.paths_per_sensor;
    if (a.overrides.count("--seed")) scene.solver.seed = scene.render.seed;
    const SolveResult r = with_progress(progress, a.quiet, [&] { return solve_openings(scene, &progress); });
    write_json(a.output, solve_result_json(scene, r));
    double total = 0.0;
    for (const auto& t : r.timings) total = t.stage == "total" ? t.seconds : total;
    std::printf("solve: %zu openings, %zu open elements; relative RMS error %.2f%% (linear model %.2f%%, "
                "compensated %.2f%%), worst sensor %.1f%%; %.2f s\nwrote %s\n",
                r.openings.size(), static_cast<size_t>(std::count(r.open.begin(), r.open.end(), 1)),
                100 * r.error.relative_rms, 100 * r.linear_error.relative_rms, 100 * r.compensated_error.relative_rms,
                100 * r.error.max_relative, total, a.output.c_str());
    return 0;
  }
  if (a.command == "contributions") {
    const Contributions c = with_progress(progress, a.quiet, [&] { return compute_contributions(scene, &progress); });
    const auto paths = write_contributions(scene, c, a.output);
    std::printf("contributions: %zu sensors x %zu elements, %d paths per sensor, %.2f s\n", c.sensor_count(),
                c.element_count(), c.paths_per_sensor, c.seconds);
    std::printf("wrote %s\nwrote %s\n", paths.first.c_str(), paths.second.c_str());
    return 0;
  }
  const auto openings = read_openings(a.openings);
  const auto start = std::chrono::steady_clock::now();
  const SensorValues v = with_progress(progress, a.quiet, [&] { return evaluate_openings(scene, openings, &progress); });
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  write_json(a.output, evaluation_json(v, openings.size(), scene.render.paths_per_sensor,
                                       unobstructed_horizontal_illuminance(scene)));
  std::printf("evaluate: %zu sensors, %zu openings, %.2f s\nwrote %s\n", scene.sensors.size(), openings.size(), seconds,
              a.output.c_str());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  const Args args = parse_args(argc, argv);
  try {
    return run(args);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "fenestra: error: %s\n", e.what());
    return 1;
  }
}
