#include "gcs/reconstructor.h"
// gcs::Reconstructor's public entry points; the loop itself is in reconstructor_setup.cpp,
// reconstructor_step.cpp, reconstructor_batch.cpp and reconstructor_post.cpp (along the concepts;
// the shared state is declared in detail/reconstructor_impl.h).

#include <algorithm>
#include <utility>

#include "detail/reconstructor_impl.h"

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
