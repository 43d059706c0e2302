#include "annual/annual_contributions.h"

#include <memory>

#include "annual/annual_records.h"

namespace fenestra {
namespace {

// A climate scene's pass: its sources, the scene that traces them, and the direct sun after.
class AnnualPass final : public SourcedPass {
 public:
  explicit AnnualPass(const Scene& scene)
      : scene_(scene), annual_(prepare_annual(scene)), traced_(annual_tracing_scene(scene, annual_->sources)) {}

  const Scene& traced_scene() const override { return traced_; }
  const SkyPatches* patches() const override { return &scene_.climate->sky->patches; }
  void chunk_traced(SensorRecord* record) const override { convert_to_design_values(*annual_, record); }
  void tracing_done(const PathTracer& tracer, int threads, SensorRange sensors, Contributions* out) override {
    record_direct_sun(scene_, tracer, annual_.get(), threads, sensors);
    out->annual = annual_;
    out->annual_bytes = annual_->memory_bytes();
  }

 private:
  const Scene& scene_;
  std::shared_ptr<AnnualRecords> annual_;
  Scene traced_;
};

}  // namespace

Contributions compute_contributions(const Scene& scene, Progress* progress, bool transport, SensorRange sensors) {
  if (!scene.climate) return trace_contributions(scene, progress, transport, sensors, nullptr);
  AnnualPass pass(scene);
  return trace_contributions(scene, progress, transport, sensors, &pass);
}

}  // namespace fenestra
