#include "study/cost_model.h"

#include "annual/annual_cut_study.h"
#include "annual/annual_study.h"
#include "annual/hourly_flip_model.h"
#include "daylight/annual_metrics.h"
#include "daylight/annual_sources.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <map>
#include <sstream>
#include <thread>

#include "daylight/daylight.h"
#include "daylight/sky_matrix.h"
#include "daylight/sky_patches.h"
#include "scene/domain_estimate.h"
#include "scene/element_size_hint.h"
#include "scene/scene.h"
#include "study/climate_reach.h"
#include "solve/catalogue_snap.h"
#include "solve/exact_values.h"
#include "solve/flip_effects_cache.h"
#include "solve/genetic.h"
#include "solve/thick_wall_edges.h"
#include "solve/thick_wall_joint_edges.h"
#include "trace/parallel.h"
#include "trace/replicates.h"
#include "util/byte_size.h"

namespace fenestra {
namespace {

// Path records (trace/path_record.h): a PathEvent is 6 bytes (a 16-bit value and one word) and its
// point (CellPoint) 4, a path adds two 4-byte offsets; light through one element, the commonest
// event, names it in the event, other events store their conditions (4 bytes and a point of 4
// each) after a header of the same size; the records are assembled with exactly the room they
// need, and 12.6-13.0 bytes per event (with the matrices) were measured on the example scenes
// (reference room, room study, paper scale). Events per path: a few at the sensor (portal
// samples, the first sky and element samples) and 1-2 per further vertex (next-event estimates,
// escapes through elements and their parts). Expected vertices: 1 + sum_{k=1..B} rho^k.
constexpr double kBytesPerEvent = 13.0, kBytesPerPath = 8.0;
// Thick walls: paths branch where they meet the elements' tubes (reveals or open neighbours); on
// thick_walls_study (0.3 m walls, 0.25 m elements) records were 7.0x (2.1x the events, each with
// several stored conditions, where the thin wall's light mostly names its one element) and
// tracing 5.7x the zero-thickness wall's for the same paths.
constexpr double kThickWallRecordFactor = 7.5, kThickWallTraceFactor = 6.0;
// A path of a cut (the openings really cut) also samples the sky through them: measured 1.53-1.72x
// the time per path (docs/solver.md, "Paths with the openings really cut"), rounded up.
constexpr double kOpeningSkySamplesTraceFactor = 1.75;
// Cuts the edge search in thick walls makes per opening (solve/thick_wall_edges.h), counting one
// of half the paths as half a cut: 125 for a window in a 0.3 m wall with 0.25 m elements (99 and
// 53 of half the paths), 123 per opening for the four of the solid off-grid two-room study; the
// pair scans over both axes are most of them.
constexpr double kThickWallEdgeCutsPerOpening = 130.0;
// Without a catalogue the edges are only placed: the start's cut and the placement's.
constexpr double kThickWallPlacementCuts = 2.0;
// Cuts of the thick-wall merges (solve/thick_wall_merges.h) per thick panel with several openings,
// a rough cut counted as half: one opening's edges searched, and the panel's candidates cut.
// Measured on the solid off-grid two-room study: 50 by single moves (free sizes), 115 with pairs of
// edges scanned (as a catalogue's are).
constexpr double kThickWallMergeCutsPerPanel = 50.0, kThickWallMergeCutsPerPanelScanned = 120.0;
// Steps of the joint edge search in thick walls (solve/thick_wall_joint_edges.h) the estimate
// assumes: it stops when a step gains under 1 %. Measured on the solid off-grid two-room study: 7
// from the placement (4 in a run with the merges' pair scans). The pair scans that follow steps
// stalled beyond the noise are left out.
constexpr double kJointEdgeStepsExpected = 6.0;
// Openings in thick walls the estimate assumes per thick panel when the constraints set no
// maximum.
constexpr double kThickWallOpeningsPerPanel = 2.0;
constexpr double kEventsAtSensor = 3.0, kEventsPerVertex = 1.75;
// While the per-task records are merged into one per sensor, both exist; the tasks' vectors keep
// up to as much spare room again as they hold.
constexpr double kRecordAssembly = 2.0;
// The edge search's index (solve/region_search.h): 17 bytes per point where a path met the domain
// (its place, path and event, and an open flag) and 8 per path, against 8 bytes per point in the
// records (a condition and its point), 10 for an event and its point; 1.6x the records where
// measured (open_region_test).
constexpr double kEdgeSearchIndexShare = 2.0;
// The exact values' index (solve/exact_values.h): 4 bytes per element a path met (at most one
// per point, against at least 8 in the records) and 8 per path for the first reference's values;
// the second reference's values are counted apart (kExactValuesSecondReferenceBytesPerPath).
constexpr double kExactValuesIndexShare = 0.5;
constexpr double kExactValuesSecondReferenceBytesPerPath = 8.0;
// The last sample's path values (ExactValues::sampled): 12 bytes for one path in kSampledShare
// at most.
constexpr double kSampledValuesBytesPerPath = 12.0 / kSampledShare;
// Embree's BVH, the tracer's triangle data and the mesh copies, per triangle.
constexpr double kRaySceneBytesPerTriangle = 256.0;
// And whatever the triangles: Embree's scene and its builder's first blocks, the tracer's tables.
// Building the tracer of a 12-triangle room (annual --cutters) added 8-52 kB resident (20 kB in
// 19 of 20 runs, 2 cores under load), 8 kB of it malloc'd; the per-triangle term gives 3 kB.
constexpr double kRaySceneFixedBytes = 64e3;
// An annual pass traces a copy of the scene (annual_tracing_scene) whose suns are the sun
// clusters: a SunLight each and 20 bytes of the choice among them (Distribution1D: two doubles and
// an int). The rest of the copy: per triangle the mesh's arrays (positions, indices, material,
// group, UVs) and the domain's triangle lists, at most 100 bytes; per element the domain's element
// and portal and its grid cell; per sensor its point, normal, goal and weight; names, materials and
// panels about 6 kB measured on a 12-triangle room (the copy's 56 kB less its 654 clusters' 50).
constexpr double kSunChoiceBytes = 20.0;
constexpr double kSceneCopyBytesPerTriangle = 100.0;
constexpr double kSceneCopyBytesPerElement = 2.0 * sizeof(Element) + 4.0;
constexpr double kSceneCopyBytesPerSensor = 2.0 * sizeof(Vec3) + 2.0 * sizeof(double);
constexpr double kSceneCopyFixedBytes = 16e3;
// Per worker thread while analysing a sensor: 16 replicate sums and A's sum per element.
constexpr double kAnalysisBytesPerElement = 8.0 * 17.0;
// The solver's copies of sensors x elements matrices: the weighted objective, the
// defect-corrected objective, NNLS's weighted matrix and work space, the refinement's prefix sums.
constexpr double kSolverCopiesOfE = 5.0;

// Reference machine (2 cores, the README's benchmark): measured rates, rounded up.
constexpr double kTraceSecondsPerVertex = 1e-6;                       // per path vertex, all cores
// A GA child: 2 us + 5 ns per (element + 4 sensors); a generation: 5 us more (measured 1.7-2.2 us
// per child at 30 sensors x 112 elements, 57-75 us at 1000 x 10000, about 3 us per generation).
constexpr double kChildSeconds = 2e-6, kChildSecondsPerUnit = 5e-9, kGenerationSeconds = 5e-6;
// Per generation of the fine run: its history record (vector) and its entry in the result's JSON.
constexpr double kHistoryBytesPerGeneration = 64.0, kHistoryJsonBytesPerGeneration = 400.0;
constexpr double kProposalSeconds = 0.5e-6, kProposalSecondsPerSensor = 10e-9;  // local search
// Time limits (docs/cost.md): the genetic stages unless solver.time_budget_s bounds the fine-grid
// runs; the local search, a polish whose default (20 000 proposals) takes milliseconds.
constexpr double kGeneticLimitSeconds = 600.0, kLocalSearchLimitSeconds = 60.0;
constexpr double kSearchSecondsPerSensorPath = 40e-9;  // a set the search over whole openings scores

double albedo(const Material& m) {
  if (m.is_glass()) return std::min(1.0, static_cast<double>(luminance(m.transmittance)) + 0.1);
  return luminance(m.reflectance);
}

// 1 + sum_{k=1..B} rho^k: the expected number of path vertices without Russian roulette.
double expected_vertices(const Scene& scene) {
  double rho = 0.0;
  for (const Material& m : scene.materials) rho = std::max(rho, albedo(m));
  rho = std::clamp(rho, 0.0, 0.99);
  double sum = 1.0, term = 1.0;
  for (int k = 1; k <= scene.render.max_bounces && term > 1e-6; ++k) sum += term *= rho;
  return sum;
}

double ray_scene_bytes(double triangles) { return kRaySceneFixedBytes + kRaySceneBytesPerTriangle * triangles; }

int worker_threads(const Scene& scene) {
  if (scene.render.threads > 0) return scene.render.threads;
  return std::max(1u, std::thread::hardware_concurrency());
}

std::string element_size_text(const Scene& scene) {
  std::ostringstream s;
  s << scene.domain.element_size();
  return s.str();
}

// What an annual pass is prepared from (annual/annual_records.cpp): the sky matrix's hours, those
// with light and with a sun cluster's sun, the sky patches and the sun clusters.
struct AnnualCounts {
  double hours = 0.0, day_hours = 0.0, sun_hours = 0.0, patches = 0.0, clusters = 0.0;
  double clustering_patches = 0.0;  // the finer patches the suns are clustered on
  double sources() const { return patches + clusters; }
};

AnnualCounts annual_counts(const SkyMatrix& sky) {
  const SunClusters suns = cluster_suns(sky);
  AnnualCounts n;
  for (size_t h = 0; h < sky.hours.size(); ++h) {
    const bool sunny = sky.sun_normal_illuminance[h] > 0.0f && suns.cluster_of_hour[h] >= 0;
    n.sun_hours += sunny;
    n.day_hours += sunny || sky.radiance.col(static_cast<Eigen::Index>(h)).maxCoeff() > 0.0f;
  }
  n.hours = static_cast<double>(sky.hours.size());
  n.patches = static_cast<double>(sky.patches.count());
  n.clusters = static_cast<double>(suns.size());
  n.clustering_patches = static_cast<double>(SkyPatches(suns.subdivision).count());
  return n;
}

// Every annual pass (the records' and the cutters'), besides the sources' day sky: the records'
// tables (each hour's sun cluster; the day and sun hours, lists grown up to twice their length;
// the clusters' directions and lux hours, grown likewise; each source's design strength and unit
// scale), and the scene it traces, held until the pass ends. Two temporaries are counted as kept:
// glibc returns a freed heap chunk's pages only from the top of the heap, so what the pass frees
// before tracing (the scene's own suns, copied with the traced scene until the clusters replace
// them; the clustering's cluster per patch and its growing sums) mostly stays resident, and the
// later allocations reuse it or not as the heap's layout falls (measured on a 12-triangle room,
// 2 cores under load: at the peak, 0.18-0.20 MB resident beyond what the run held in 4 of 24
// runs, 0.38-0.68 MB less in the others, where the first run's freed pages were reused).
void add_annual_preparation(const Scene& scene, const AnnualCounts& n, CostEstimate* e) {
  e->memory.push_back({"annual_tables", "the annual pass's hourly tables (sun clusters, day and sun hours)",
                       4.0 * n.hours + 2.0 * 4.0 * (n.day_hours + n.sun_hours) +
                           2.0 * (sizeof(Vec3) + sizeof(double)) * n.clusters + 2.0 * sizeof(double) * n.sources(),
                       "", "a weather file of fewer hours"});
  e->memory.push_back({"traced_scene", "the scene traced under the annual sources (a copy, with the sun clusters)",
                       (sizeof(SunLight) + kSunChoiceBytes) * n.clusters +
                           kSceneCopyBytesPerTriangle * static_cast<double>(e->triangles) +
                           kSceneCopyBytesPerElement * static_cast<double>(e->elements) +
                           kSceneCopyBytesPerSensor * static_cast<double>(e->sensors) + kSceneCopyFixedBytes,
                       "", "fewer triangles or sensors"});
  e->memory.push_back({"scene_suns_copy", "the scene's suns, copied with the traced scene until the clusters replace "
                       "them (freed, their pages kept by the heap)",
                       (sizeof(SunLight) + kSunChoiceBytes) * static_cast<double>(scene.suns.suns().size()), "",
                       "a shorter sky.occupied period"});
  e->memory.push_back({"sun_clustering", "the sun clustering's working arrays (freed, their pages kept by the heap)",
                       sizeof(int) * n.clustering_patches + 3.0 * sizeof(Eigen::Vector3d) * n.clusters, "",
                       "a weather file of fewer hours"});
}

// A climate sky's annual pass: each event's source and coefficient (6 bytes), the sun straight to
// each sensor at each sunny hour (an event, its point, its exact factor and a condition or two:
// under 48 bytes), and a study's hourly illuminance (total and direct sun, floats) with the file's
// copy.
void add_annual(const Scene& scene, double records, CostEstimate* e) {
  const double S = static_cast<double>(e->sensors);
  const SkyMatrix& sky = *scene.climate->sky;
  double sunny = 0.0;
  for (float x : sky.sun_normal_illuminance) sunny += x > 0.0f;
  const double hours = static_cast<double>(sky.hours.size());
  e->memory.push_back({"annual_sources", "the events' sources and daylight coefficients", records * 6.0 / kBytesPerEvent,
                       "", "fewer paths (render.paths_per_sensor, --paths)"});
  e->memory.push_back({"direct_sun", "the sun seen from each sensor at each sunny hour", 48.0 * S * sunny, "",
                       "fewer sensors"});
  e->memory.push_back({"annual_illuminance", "the hourly illuminance of an annual study (sensors x hours, twice, and "
                       "its file)", 4.0 * 4.0 * S * hours, "writing", "fewer sensors"});
  const AnnualCounts n = annual_counts(sky);
  e->memory.push_back({"annual_day_sky", "the sources' day sky (sky patches x day hours)", 4.0 * n.patches * n.day_hours,
                       "", "fewer sky patches (sky.patches)"});
  add_annual_preparation(scene, n, e);
}

void add_contributions(const Scene& scene, long long paths, CostEstimate* e) {
  const double S = static_cast<double>(e->sensors), N = static_cast<double>(e->elements);
  const std::string fewer_elements = kLargerElementSize;
  const std::string fewer_paths = e->command == CostCommand::Solve ? "fewer paths (solver.paths, render.paths_per_sensor, --paths)"
                                                                   : "fewer paths (render.paths_per_sensor, --paths)";
  e->memory.push_back({"E", "the contribution matrix E (sensors x elements)", 8 * S * N, "",
                       "fewer sensors or " + fewer_elements});
  e->memory.push_back({"E_stderr", "E's standard errors (sensors x elements)", 8 * S * N, "",
                       "fewer sensors or " + fewer_elements});
  e->memory.push_back({"A", "the error-compensation matrix A (sensors x elements)", 8 * S * N, "",
                       "fewer sensors or " + fewer_elements});
  e->memory.push_back({"T", "the error-compensation matrix T (elements x elements)", 8 * N * N, "", fewer_elements});
  const double records = S * static_cast<double>(paths) * e->bytes_per_path;
  e->memory.push_back({"path_records", "the path records (sensors x paths)", records, "", fewer_paths});
  e->memory.push_back({"path_records_assembly", "the path records while they are assembled",
                       kRecordAssembly * records, "tracing", fewer_paths, true});
  // T is symmetrised in place (trace/transport_matrix.h); a second T stays counted while it is
  // assembled: the margin of the largest studies, whose T dominates everything else.
  e->memory.push_back({"T_symmetrised", "a margin of T's size while it is assembled", 8 * N * N, "tracing",
                       fewer_elements, true});
  e->memory.push_back({"analysis", "per-thread analysis buffers", kAnalysisBytesPerElement * N * worker_threads(scene),
                       "tracing", fewer_elements});
  // The stratified sampler's per-sensor choice of portal samples (trace/portal_selection.h): a
  // 32-bit interval start per sensor and element, while the paths are traced.
  if (scene.render.sampler == RenderSettings::Sampler::kSobol)
    e->memory.push_back({"portal_selection", "each sensor's choice of portal samples (sensors x elements)", 4 * S * N,
                         "tracing", "fewer sensors or " + fewer_elements});
  if (scene.climate && scene.climate->sky) add_annual(scene, records, e);
  e->time.push_back({"tracing", "tracing the contribution paths",
                     S * static_cast<double>(paths) * expected_vertices(scene) * kTraceSecondsPerVertex *
                         (scene.domain.has_thick_walls() ? kThickWallTraceFactor : 1.0),
                     0.0,
                     fewer_paths});
}

// The columns of the climate goals' hourly model (annual/hourly_flip_model.h's hourly_columns):
// the lit hours of the occupied period and, with an EN 17037 goal, its daylight hours.
double climate_columns(const Scene& scene) {
  const SkyMatrix& sky = *scene.climate->sky;
  const AnnualMetricSettings settings = annual_metric_settings(scene);
  bool en17037 = false;
  for (const ClimateGoal& g : scene.sensors.climate_goals.goals) en17037 = en17037 || g.metric == ClimateMetric::En17037;
  std::vector<char> daylight;
  if (en17037) daylight = en17037_daylight_hours(sky.diffuse_horizontal_lux);
  double columns = 0.0;
  for (size_t h = 0; h < sky.hours.size(); ++h) {
    const bool lit = sky.sun_normal_illuminance[h] > 0.0f || sky.radiance.col(static_cast<Eigen::Index>(h)).maxCoeff() > 0.0f;
    const int clock = sky.hours[h].clock_hour;
    const bool occupied = clock >= settings.occupied_start_hour && clock < settings.occupied_end_hour;
    columns += lit && (occupied || (en17037 && daylight[h]));
  }
  return columns;
}

// Climate goals (solve/climate_design.h): the hourly model, every element's change of each goal
// sensor's year where the sensor's light meets the element (study/climate_reach.h estimates those
// pairs from what each sensor sees: the records count them exactly before the model is built), one
// model at a time; and each individual's year (total and direct sun) in the search's slots.
void add_climate_goals(const Scene& scene, CostEstimate* e) {
  const std::vector<double> reach = climate_reach(scene);
  double rows = 0.0, pairs = 0.0;
  for (double r : reach) rows += r > 0.0, pairs += r;
  const double columns = climate_columns(scene), pop = scene.solver.population;
  const std::string fewer = "fewer sensors in the climate goals or " + std::string(kLargerElementSize);
  e->memory.push_back({"climate_model", "the climate goals' hourly model (goal sensors x hours x the elements each "
                       "sensor's light meets, estimated)",
                       hourly_flip_model_bytes(rows, columns, pairs), "solving", fewer});
  // A slot per individual and per child, and the polish's (solve/genetic_search.h); the direct sun's
  // hours only for an ASE goal.
  bool ase = false;
  for (const ClimateGoal& g : scene.sensors.climate_goals.goals) ase = ase || g.metric == ClimateMetric::SunlightExposure;
  e->memory.push_back({"climate_population", "the genetic algorithm's years (goal sensors x hours per individual)",
                       (2.0 * pop + 1.0) * (ase ? 8.0 : 4.0) * rows * columns, "solving",
                       "a smaller solver.population, or " + fewer});
}

void add_solver(const Scene& scene, CostEstimate* e) {
  const SolverSettings& s = scene.solver;
  const double S = static_cast<double>(e->sensors), N = static_cast<double>(e->elements);
  const double pop = s.population, gens = s.generations;
  e->memory.push_back({"solver_copies", "the solver's copies of E", kSolverCopiesOfE * 8 * S * N, "solving",
                       "fewer sensors or " + std::string(kLargerElementSize)});
  // The linearisations' flip effects kept for the next about the same set (solve/flip_effects_cache.h).
  const double flip_effects = 8.0 * S * N;
  e->memory.push_back({"flip_effects_kept", "the flip effects kept for linearising about the same openings again",
                       flip_effects <= static_cast<double>(kFlipEffectsCacheBytes)
                           ? std::min(static_cast<double>(kFlipEffectsCacheBytes), kFlipEffectsKept * flip_effects)
                           : 0.0,
                       "solving", "fewer sensors or " + std::string(kLargerElementSize)});
  const bool thick_edges = s.refine_edges && scene.domain.has_thick_walls();
  if (s.verify || thick_edges)
    e->memory.push_back({"verification_scene", "the ray-tracing scene of a cut (the verification, thick walls' edges)",
                         ray_scene_bytes(static_cast<double>(e->triangles)), "solving", "fewer triangles"});
  e->memory.push_back({"population", "the genetic algorithm's populations", 3 * pop * (N + 8 * S + 64), "solving",
                       "a smaller solver.population"});
  if (!scene.sensors.climate_goals.empty() && scene.climate && scene.climate->sky) add_climate_goals(scene, e);
  const double path_records = S * static_cast<double>(e->paths_per_sensor) * e->bytes_per_path;
  e->memory.push_back({"exact_values_index", "the exact evaluation's index of the elements each path met",
                       kExactValuesIndexShare * path_records +
                           (kExactValuesSecondReferenceBytesPerPath + kSampledValuesBytesPerPath) * S *
                               static_cast<double>(e->paths_per_sensor),
                       "solving", "fewer solver paths"});
  // Every set the search over whole openings scores keeps its exact values (a value and a standard
  // error per sensor) and its open mask, with the map's nodes.
  e->memory.push_back({"opening_search_values", "the exact values of the sets the search over whole openings scores",
                       s.search_evaluations * (16.0 * S + N + 96.0), "solving", "fewer solver.search_evaluations"});
  if (s.refine_edges) {
    e->memory.push_back({"edge_search_index", "the edge search's index of where paths met the domain",
                         kEdgeSearchIndexShare * path_records, "solving", "fewer solver paths, or solver.refine_edges off"});
  }
  if (thick_edges) {
    // Which elements each sensor's records met, so that a cut traces only the sensors a change
    // can reach (solve/change_reach.h).
    e->memory.push_back({"change_reach", "the elements each sensor's records met (which sensors a cut must trace)",
                         S * N, "solving", "fewer sensors or " + std::string(kLargerElementSize)});
    // Edges in thick walls: openings really cut (solve/thick_wall_edges.h), each with at most
    // thick_wall_cut_paths paths per sensor through the wall; searched by pairs of edges only
    // with a catalogue, else placed.
    int thick_panels = 0;
    for (const Panel& p : scene.domain.panels()) thick_panels += p.thickness > 0.0f;
    const double openings = s.constraints.max_openings > 0 ? s.constraints.max_openings
                                                           : kThickWallOpeningsPerPanel * thick_panels;
    const bool searched = uses_catalogue(scene.domain, s.constraints);
    const double cuts = searched ? kThickWallEdgeCutsPerOpening * openings : kThickWallPlacementCuts;
    const int solver_paths = static_cast<int>(std::min<long long>(e->paths_per_sensor, 1 << 30));
    const double paths = thick_wall_cut_paths(solver_paths);
    const double cut_seconds_per_path =
        expected_vertices(scene) * kTraceSecondsPerVertex * kThickWallTraceFactor * kOpeningSkySamplesTraceFactor;
    e->time.push_back({"thick_wall_edges",
                       std::string(searched ? "cutting the openings the edge search in thick walls tries"
                                            : "cutting the openings in thick walls where the records place their edges") +
                           " (about " + format_count(cuts) + " cuts of " + format_count(paths) + " paths per sensor)",
                       cuts * S * paths * cut_seconds_per_path,
                       0.0, "fewer openings (solver.constraints.max_openings), or solver.refine_edges off"});
    // Each thick panel that can hold several of those openings is tried with one.
    const double merged_panels = std::min<double>(thick_panels, std::floor(openings / 2.0));
    if (merged_panels > 0.0) {
      const double merge_cuts =
          (searched ? kThickWallMergeCutsPerPanelScanned : kThickWallMergeCutsPerPanel) * merged_panels;
      e->time.push_back({"thick_wall_merges",
                         "cutting the openings the thick-wall merges try (about " + format_count(merge_cuts) +
                             " cuts of " + format_count(paths) + " paths per sensor)",
                         merge_cuts * S * paths * cut_seconds_per_path,
                         0.0, "fewer openings (solver.constraints.max_openings), or solver.refine_edges off"});
    }
    // Every side moved at once: per step two cuts per side, and a judged cut of more paths per
    // damping tried.
    const double judge_paths = joint_edge_judge_paths(thick_wall_cut_paths(solver_paths), solver_paths);
    const double joint_cut_paths =
        kJointEdgeStepsExpected * (8.0 * openings * paths + std::size(kJointEdgeDampings) * judge_paths);
    e->time.push_back({"thick_wall_joint_edges",
                       "cutting the openings the joint edge steps in thick walls try (about " +
                           format_count(kJointEdgeStepsExpected * 8.0 * openings) + " cuts of " + format_count(paths) +
                           " paths per sensor and " +
                           format_count(kJointEdgeStepsExpected * std::size(kJointEdgeDampings)) + " of " +
                           format_count(judge_paths) + ")",
                       joint_cut_paths * S * cut_seconds_per_path,
                       0.0, "fewer openings (solver.constraints.max_openings), or solver.refine_edges off"});
    // The openings chosen again for their edges off the grid (solve/refinable_openings.h): at most
    // search_evaluations sets more, each kept twice (the records' exact values, and the search's
    // values) and evaluated as the search's are.
    e->memory.push_back({"thick_wall_openings_values",
                         "the values of the sets the choice of openings in thick walls evaluates",
                         s.search_evaluations * (24.0 * S + N + 160.0), "solving", "fewer solver.search_evaluations"});
    e->time.push_back({"thick_wall_openings", "the choice of openings in thick walls (at most)",
                       s.search_evaluations * S * static_cast<double>(e->paths_per_sensor) * kSearchSecondsPerSensorPath,
                       0.0, "fewer solver.search_evaluations (" + format_count(s.search_evaluations) + ")"});
  }
  // Children bred: the fine-grid run and its defect-corrected rerun (a quarter as long), and
  // with coarse_to_fine two coarse levels at half the generations each.
  const double child = kChildSeconds + kChildSecondsPerUnit * (N + 4 * S);
  double fine = gens * (pop * child + kGenerationSeconds), second = 0.25 * fine;
  if (s.time_budget_s > 0.0) fine = std::min(fine, s.time_budget_s), second = std::min(second, s.time_budget_s);
  const double coarse_child = kChildSeconds + kChildSecondsPerUnit * (N / 4 + 4 * S);
  const double coarse = s.coarse_to_fine ? gens * (pop * coarse_child + kGenerationSeconds) : 0.0;
  const double records = std::min<double>(gens, kMaxHistory);  // the history is thinned beyond
  e->memory.push_back({"genetic_history", "the genetic algorithm's history (a record per generation, thinned)",
                       kHistoryBytesPerGeneration * records, "solving", "fewer solver.generations"});
  e->memory.push_back({"result_history", "the result's genetic history (JSON)", kHistoryJsonBytesPerGeneration * records,
                       "writing", "fewer solver.generations"});
  // With a time budget the user chose the fine-grid runs' length; the coarse levels (which the
  // budget does not bound) are still held to the limit.
  e->time.push_back({"genetic", "the genetic algorithm", fine + second + coarse,
                     kGeneticLimitSeconds + (s.time_budget_s > 0.0 ? fine + second : 0.0),
                     "fewer solver.generations (" + format_count(gens) + ") or a smaller solver.population (" +
                         format_count(pop) + "), or a solver.time_budget_s"});
  // The exact search over whole openings: each set it scores re-evaluates the paths that met the
  // elements it changes (measured about 31 ns per sensor and path in a 0.3 m solid wall, the share
  // of paths included: 44 ns on a machine whose tracing took 1.4 times as long); an upper bound,
  // as the search mostly stops before its limit.
  e->time.push_back({"opening_search", "the exact search over whole openings (at most)",
                     s.search_evaluations * S * static_cast<double>(e->paths_per_sensor) * kSearchSecondsPerSensorPath,
                     0.0, "fewer solver.search_evaluations (" + format_count(s.search_evaluations) + ")"});
  e->time.push_back({"local_search", "the local search over openings",
                     s.improve_iterations * (kProposalSeconds + kProposalSecondsPerSensor * S), kLocalSearchLimitSeconds,
                     "fewer solver.improve_iterations (" + format_count(s.improve_iterations) + ")"});
}

// An annual study traced with the openings cut (annual/annual_cut_study.cpp): per sensor and task
// of kPathsPerTask paths its replicate sums, while tracing a batch of sensors their tasks' rows of
// coefficients (one double per source; batches of 64 MB unless one sensor's rows alone are larger),
// and kept the coefficients (sensors x sources doubles, sensors x sun hours floats) and the sources'
// day sky; the year's illuminance while it is written.
void add_annual_cutters(const Scene& scene, CostEstimate* e) {
  const double S = static_cast<double>(e->sensors), P = static_cast<double>(e->paths_per_sensor);
  const AnnualCounts n = annual_counts(*scene.climate->sky);
  const double sources = n.sources(), sun_hours = n.sun_hours;
  const double tasks = std::ceil(P / kPathsPerTask);
  const double row_bytes = sizeof(double) * sources * tasks;  // one sensor's rows
  const double batch = std::min(S, std::max(1.0, std::floor(kAnnualCutBatchBytes / row_bytes)));
  const std::string fewer_paths = "fewer paths (render.paths_per_sensor, --paths)";
  e->memory.push_back({"task_sums", "the paths' replicate sums (sensors x tasks of " + std::to_string(kPathsPerTask) +
                       " paths)", sizeof(ReplicateSums) * S * tasks, "tracing", fewer_paths});
  e->memory.push_back({"task_rows", "the coefficients of a batch of sensors' tasks (tasks x sources)",
                       row_bytes * batch, "tracing", fewer_paths});
  e->memory.push_back({"annual_coefficients", "the sensors' daylight coefficients (sensors x sources and sun hours)",
                       S * (8.0 * sources + 4.0 * sun_hours), "", "fewer sensors"});
  e->memory.push_back({"annual_sources", "the sources' day sky (sky patches x day hours)",
                       4.0 * n.patches * n.day_hours, "", "fewer sky patches (sky.patches)"});
  e->memory.push_back({"annual_illuminance", "the hourly illuminance of an annual study (sensors x hours, twice, and "
                       "its file)", 4.0 * 4.0 * S * n.hours, "writing", "fewer sensors"});
  add_annual_preparation(scene, n, e);
  e->time.push_back({"tracing", "tracing the year's paths with the openings cut",
                     S * P * expected_vertices(scene) * kTraceSecondsPerVertex *
                         (scene.domain.has_thick_walls() ? kThickWallTraceFactor : 1.0),
                     0.0, fewer_paths});
}

// Writing OUT.npz: every array once more in the archive's buffers, plus one row-major copy.
void add_output(CostEstimate* e) {
  const double S = static_cast<double>(e->sensors), N = static_cast<double>(e->elements);
  e->memory.push_back({"npz_buffers", "the .npz file's buffers", 8 * (3 * S * N + N * N) + 8 * std::max(S * N, N * N),
                       "writing", "fewer sensors or " + std::string(kLargerElementSize), true});
}

std::string describe_sizes(const Scene& scene, const CostEstimate& e, const MemoryItem& item) {
  std::ostringstream s;
  if (item.key == "T" || item.key == "T_symmetrised" || item.key == "analysis")
    s << "opening_domain.element_size " << element_size_text(scene) << " m gives " << format_count(e.elements)
      << " elements";
  else if (item.key.rfind("task_", 0) == 0)
    s << format_count(static_cast<double>(e.paths_per_sensor)) << " paths per sensor for " << format_count(e.sensors)
      << " sensors, in tasks of " << kPathsPerTask << " paths";
  else if (item.key.rfind("path_records", 0) == 0)
    s << format_count(static_cast<double>(e.paths_per_sensor)) << " paths per sensor for " << format_count(e.sensors)
      << " sensors (about " << std::lround(e.bytes_per_path) << " bytes of records per path)";
  else if (item.key == "population")
    s << "solver.population " << format_count(scene.solver.population) << " over " << format_count(e.elements)
      << " elements";
  else if (item.key == "sky_image")
    s << "the sky map";
  else
    s << format_count(e.sensors) << " sensors x " << format_count(e.elements) << " elements (element_size "
      << element_size_text(scene) << " m)";
  return s.str();
}

}  // namespace

double path_record_bytes(const Scene& scene) {
  const double thin = kBytesPerPath + kBytesPerEvent * (kEventsAtSensor + kEventsPerVertex * expected_vertices(scene));
  return scene.domain.has_thick_walls() ? kThickWallRecordFactor * thin : thin;
}

double CostEstimate::kept_bytes() const {
  double sum = 0.0;
  for (const MemoryItem& m : memory)
    if (m.phase.empty()) sum += m.bytes;
  return sum;
}

double CostEstimate::peak_bytes() const {
  std::map<std::string, double> stages;
  for (const MemoryItem& m : memory)
    if (!m.phase.empty()) stages[m.phase] += m.bytes;
  double transient = 0.0;
  for (const auto& stage : stages) transient = std::max(transient, stage.second);
  return kept_bytes() + transient;
}

const MemoryItem* CostEstimate::largest_to_name() const {
  const MemoryItem *kept = nullptr, *transient = nullptr;
  for (const MemoryItem& m : memory) {
    if (m.copy) continue;
    const MemoryItem*& best = m.phase.empty() ? kept : transient;
    if (!best || m.bytes > best->bytes) best = &m;
  }
  // A stage's working copies of kept items (records while assembled, T's margin while assembled, the
  // file's buffers) are named through what is kept; other transient items when they dominate.
  if (!kept || (transient && transient->bytes > 2.0 * kept->bytes)) return transient;
  return kept;
}

CostCommand cost_command(const std::string& name) {
  static const std::map<std::string, CostCommand> kNames = {
      {"any", CostCommand::Any},     {"contributions", CostCommand::Contributions}, {"evaluate", CostCommand::Evaluate},
      {"solve", CostCommand::Solve}, {"solver", CostCommand::Solver},               {"sky", CostCommand::Sky},
      {"annual_cutters", CostCommand::AnnualCutters}};
  const auto it = kNames.find(name);
  if (it == kNames.end())
    throw std::invalid_argument("unknown command '" + name.substr(0, 80) +
                                "' (contributions, evaluate, solve, solver, sky, annual_cutters or any)");
  return it->second;
}

std::string cost_command_name(CostCommand command) {
  switch (command) {
    case CostCommand::Contributions: return "contributions";
    case CostCommand::Evaluate: return "evaluate";
    case CostCommand::Solve: return "solve";
    case CostCommand::Solver: return "solver";
    case CostCommand::Sky: return "sky";
    case CostCommand::AnnualCutters: return "annual_cutters";
    default: return "any";
  }
}

CostEstimate estimate_cost(const Scene& scene, CostCommand command, double elements, double paths) {
  CostEstimate e;
  e.command = command;
  e.sensors = scene.sensors.size();
  e.elements = elements >= 0.0 ? static_cast<size_t>(std::llround(elements)) : scene.domain.element_count();
  e.triangles = scene.mesh.triangle_count();
  e.paths_per_sensor = scene.render.paths_per_sensor;
  if ((command == CostCommand::Solve || command == CostCommand::Solver) && scene.solver.paths_per_sensor > 0)
    e.paths_per_sensor = scene.solver.paths_per_sensor;
  if (paths >= 0.0) e.paths_per_sensor = static_cast<int>(std::llround(paths));
  e.bytes_per_path = path_record_bytes(scene);
  const double ray_scene = ray_scene_bytes(static_cast<double>(e.triangles));
  switch (command) {
    case CostCommand::Any:
    case CostCommand::Contributions:
    case CostCommand::Solve:
      add_contributions(scene, e.paths_per_sensor, &e);
      e.memory.push_back({"ray_scene", "the ray-tracing scene (BVH)", ray_scene, "tracing", "fewer triangles"});
      if (command == CostCommand::Solve) add_solver(scene, &e);
      if (command == CostCommand::Contributions) add_output(&e);
      break;
    case CostCommand::Solver:
      add_solver(scene, &e);
      break;
    case CostCommand::Evaluate:
      e.memory.push_back({"ray_scene", "the ray-tracing scene (BVH)", ray_scene, "tracing", "fewer triangles"});
      e.time.push_back({"tracing", "tracing the sensors' paths",
                        static_cast<double>(e.sensors) * static_cast<double>(e.paths_per_sensor) *
                            expected_vertices(scene) * kTraceSecondsPerVertex,
                        0.0, "fewer paths (render.paths_per_sensor, --paths)"});
      break;
    case CostCommand::AnnualCutters:
      e.memory.push_back({"ray_scene", "the ray-tracing scene (BVH)", ray_scene, "tracing", "fewer triangles"});
      if (scene.climate && scene.climate->sky) add_annual_cutters(scene, &e);
      break;
    case CostCommand::Sky: {
      const double pixels = scene.daylight ? static_cast<double>(scene.daylight->width) * scene.daylight->height
                                           : 1024.0 * 512.0;
      e.memory.push_back({"sky_image", "the sky map and its file buffers", 36.0 * pixels, "writing",
                          "a smaller sky.resolution"});
      break;
    }
  }
  return e;
}

std::string memory_summary(const Scene& scene, CostCommand command, const MemoryLimit& limit) {
  const CostEstimate e = estimate_cost(scene, command);
  std::ostringstream s;
  for (const MemoryItem& m : e.memory)
    if (m.key == "path_records")
      s << "path records " << format_bytes(m.bytes) << " (" << format_count(e.paths_per_sensor) << " paths per sensor x "
        << format_count(static_cast<double>(e.sensors)) << " sensors), ";
  s << format_bytes(e.peak_bytes()) << " at the peak; " << format_bytes(static_cast<double>(limit.bytes)) << " "
    << limit.source;
  return s.str();
}

// ": at most N per sensor fit" (N the most paths whose peak stays under the limit), or "" when
// not even one path fits.
std::string paths_that_fit(const Scene& scene, CostCommand command, const CostEstimate& e, const MemoryLimit& limit) {
  if (e.paths_per_sensor <= 1) return "";
  auto fits = [&](double n) { return estimate_cost(scene, command, -1.0, n).peak_bytes() <= static_cast<double>(limit.bytes); };
  double lo = 1.0, hi = static_cast<double>(e.paths_per_sensor);
  if (!fits(lo)) return "";
  while (hi - lo > 1.0) {  // the peak grows with the paths
    const double mid = std::floor(0.5 * (lo + hi));
    (fits(mid) ? lo : hi) = mid;
  }
  return ": at most " + format_count(lo) + " per sensor fit";
}

void check_cost(const Scene& scene, CostCommand command, const MemoryLimit& limit, double paths) {
  const CostEstimate e = estimate_cost(scene, command, -1.0, paths);
  const std::string prefix = "scene '" + scene.source + "': ";
  const double peak = e.peak_bytes();
  if (peak > static_cast<double>(limit.bytes)) {
    const MemoryItem& big = *e.largest_to_name();
    std::string setting = big.setting;
    const size_t generic = setting.find(kLargerElementSize);
    if (generic != std::string::npos) {  // name the element size that fits
      const double fits = element_size_that_fits(
          scene.domain.element_size(), static_cast<double>(e.elements),
          [&](double n) { return estimate_cost(scene, command, n, paths).peak_bytes(); }, static_cast<double>(limit.bytes),
          kMaxElements);
      setting.replace(generic, std::string(kLargerElementSize).size(), larger_element_size(fits));
    }
    if (setting.rfind("fewer paths", 0) == 0) setting += paths_that_fit(scene, command, e, limit);
    throw CostError(prefix + describe_sizes(scene, e, big) + "; " +
                    memory_refusal(big.description + (peak > 1.05 * big.bytes ? " alone" : ""), big.bytes, peak, limit,
                                   setting));
  }
  for (const TimeItem& t : e.time) {
    if (t.limit_seconds <= 0.0 || t.seconds <= t.limit_seconds) continue;
    std::ostringstream s;
    s << prefix << t.description << " would take about " << std::lround(t.seconds / 60.0) << " min ("
      << format_count(t.seconds) << " s on the 2-core reference machine; at most " << format_count(t.limit_seconds)
      << " s): use " << t.setting;
    throw CostError(s.str());
  }
}

void check_cost(const Scene& scene, CostCommand command) { check_cost(scene, command, memory_limit()); }

}  // namespace fenestra
