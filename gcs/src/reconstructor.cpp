#include "gcs/reconstructor.h"
// gcs::Reconstructor's public entry points; the loop itself is in reconstructor_setup.cpp,
// reconstructor_step.cpp, reconstructor_batch.cpp and reconstructor_post.cpp (along the concepts;
// the shared state is declared in detail/reconstructor_impl.h).

#include <algorithm>
#include <string>
#include <utility>
#include <vector>

#include "detail/reconstructor_impl.h"
#include "edgefront/error.h"

namespace gcs {

std::string to_string(Phase phase) {
  switch (phase) {
    case Phase::noise_estimate:
      return "noise estimate";
    case Phase::normal_fitting:
      return "normal fitting";
    case Phase::growth:
      return "growth";
    case Phase::post_processing:
      return "post-processing";
  }
  return "unknown phase";
}

std::string to_string(StopReason reason) {
  switch (reason) {
    case StopReason::target_reached:
      return "target reached";
    case StopReason::cancelled:
      return "cancelled";
    case StopReason::step_limit:
      return "step limit";
    case StopReason::shrunk_by_operations:
      return "below the target: the operations removed parts again after regrowing";
  }
  return "unknown";
}

ReconstructOptions ReconstructOptions::scan() { return {}; }

ReconstructOptions ReconstructOptions::thin_shell() {
  ReconstructOptions o;
  // With input normals: the missing layer of a wall grows back from its border instead of the
  // other wall being dented into the gap (bench/results/gcs.md, "skip_unfaced_samples with the
  // resolution"; bench/results/twist-vaults.md).
  o.experimental.skip_unfaced_samples = true;
  // Without normals: the plane fits are undefined or wrongly oriented where the walls are about a
  // neighbourhood apart; the quadric fits are not (bench/results/gcs.md, "fitted normals").
  o.input.quadric_normals = true;
  return o;
}

ReconstructOptions ReconstructOptions::open_sheet() {
  ReconstructOptions o;
  // Without normals: the quadric fits orient an open sheet consistently where the plane fits leave
  // it in patches (bench/results/gcs.md, "fitted normals": the groin vault).
  o.input.quadric_normals = true;
  // An open sheet has true borders only: none is closed.
  o.post.close_false_borders = false;
  return o;
}

namespace {

/// The presets by name, in the order preset_names() lists them (the one list of them).
struct NamedPreset {
  const char* name;
  ReconstructOptions (*make)();
};
constexpr NamedPreset kPresets[] = {{"scan", &ReconstructOptions::scan},
                                    {"thin_shell", &ReconstructOptions::thin_shell},
                                    {"open_sheet", &ReconstructOptions::open_sheet}};

}  // namespace

std::vector<std::string> ReconstructOptions::preset_names() {
  std::vector<std::string> names;
  for (const NamedPreset& p : kPresets) names.emplace_back(p.name);
  return names;
}

ReconstructOptions ReconstructOptions::preset(const std::string& name) {
  for (const NamedPreset& p : kPresets) {
    if (name == p.name) return p.make();
  }
  std::string names;
  for (const std::string& n : preset_names()) names += (names.empty() ? "" : ", ") + n;
  throw InvalidInput("gcs: unknown options preset '" + name + "' (presets: " + names + ")");
}

Reconstructor::Reconstructor(edgefront::PointCloud points, const ReconstructOptions& options,
                             const ProgressCallback& progress)
    : impl_(std::make_unique<Impl>()) {
  impl_->init(std::move(points), options, progress);
}
Reconstructor::~Reconstructor() = default;

void Reconstructor::add_operation(std::shared_ptr<Operation> operation) {
  if (!operation) throw InvalidInput("gcs: add_operation needs an operation (got a null pointer)");
  Impl::Registered r;
  r.report.name = operation->name();
  r.op = std::move(operation);
  r.last = 0;
  impl_->ops.push_back(std::move(r));
}

ReconstructResult Reconstructor::run(const ProgressCallback& progress) { return impl_->run(progress); }
const Mesh& Reconstructor::mesh() const { return impl_->mesh; }
Vec3 Reconstructor::offset() const { return impl_->offset; }
void Reconstructor::validate() const { impl_->validate(); }
void Reconstructor::run_basic_steps(std::uint64_t n) {
  impl_->basic_steps(n);
}

ReconstructResult reconstruct(edgefront::PointCloud points, const ReconstructOptions& options,
                              const ProgressCallback& progress) {
  Reconstructor r(std::move(points), options, progress);
  return r.run(progress);
}

size_t max_target_vertices(const edgefront::PointCloud& points) {
  edgefront::PointCloud copy;
  copy.points = points.points;
  detail::drop_repeated_points(copy);
  return std::min<size_t>(copy.size(), 50'000'000);
}

}  // namespace gcs
