#include "edgefront/batch_distance.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <utility>

#include "edgefront/arrays.h"
#include "edgefront/error.h"
#include "edgefront/front_source.h"
#include "edgefront/geodesic_ring_table.h"
#include "edgefront/parallel.h"
#include "edgefront/vertex_twins.h"

namespace edgefront {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

void check_vertices(const Mesh& mesh, std::span<const VertexHandle> vs, const char* what) {
  const std::size_t n = mesh.n_vertices();
  for (std::size_t i = 0; i < vs.size(); ++i) {
    const VertexHandle v = vs[i];
    if (!v.is_valid() || static_cast<std::size_t>(v.idx()) >= n) {
      throw InvalidInput(std::string("geodesic_distances: ") + what + " " + std::to_string(i) + " (vertex " +
                         std::to_string(v.idx()) + ") is outside [0, " + std::to_string(n) + ")");
    }
    if (mesh.has_vertex_status() && mesh.status(v).deleted()) {
      throw InvalidInput(std::string("geodesic_distances: ") + what + " " + std::to_string(i) + " (vertex " +
                         std::to_string(v.idx()) + ") is deleted");
    }
  }
}

// The batch itself. `targets` null: every vertex is a column.
DistanceMatrix run_batch(const Mesh& mesh, std::span<const VertexHandle> sources,
                         const std::vector<VertexHandle>* targets, const DistanceOptions& options,
                         const BatchOptions& batch) {
  if (sources.empty()) throw InvalidInput("geodesic_distances: no source vertex given");
  check_vertices(mesh, sources, "source");
  if (targets) {
    if (targets->empty()) throw InvalidInput("geodesic_distances: no target vertex given");
    check_vertices(mesh, *targets, "target");
  }
  if (options.target) {
    throw InvalidInput("geodesic_distances: DistanceOptions::target is not used by a batch (pass the targets)");
  }
  if (!(options.max_distance >= 0)) {
    throw InvalidInput("geodesic_distances: max_distance must be >= 0 (got " + std::to_string(options.max_distance) +
                       ")");
  }
  const std::size_t n = mesh.n_vertices();
  DistanceOptions o = options;
  o.directions = false;

  DistanceMatrix out;
  out.rows = sources.size();
  out.columns = targets ? targets->size() : n;
  out.values.assign(out.rows * out.columns, kNaN);
  out.stop.assign(out.rows, DistanceStop::NotStarted);
  out.computed.assign(out.rows, 0);
  out.threads = threads_for(out.rows, batch.threads);

  // Columns of each target vertex: first_column[v] and then next_column[j] (-1 ends the list).
  std::vector<int> first_column, next_column;
  std::size_t distinct_targets = 0;
  if (targets) {
    first_column.assign(n, -1);
    next_column.assign(targets->size(), -1);
    for (std::size_t j = targets->size(); j-- > 0;) {
      int& head = first_column[static_cast<std::size_t>((*targets)[j].idx())];
      if (head < 0) ++distinct_targets;
      next_column[j] = head;
      head = static_cast<int>(j);
    }
  }

  const bool stepwise = o.method == DistanceMethod::Mdf || o.method == DistanceMethod::Windows;
  std::unique_ptr<GeodesicRingTable> table;
  if (!stepwise && sources.size() >= 2) {
    table = std::make_unique<GeodesicRingTable>(mesh);
    out.table_bytes = table->memory_bytes();
  }

  std::vector<std::unique_ptr<MinimalDistanceFront>> fronts(out.threads);
  std::vector<std::size_t> worker_peak(out.threads, 0);
  std::mutex progress_mutex;
  std::size_t done = 0;
  bool cancelled = false;

  auto row_done = [&](std::size_t i, DistanceStop stop) -> bool {
    const std::lock_guard<std::mutex> lock(progress_mutex);
    out.stop[i] = stop;
    out.computed[i] = 1;
    ++done;
    if (batch.progress && !cancelled && !batch.progress(done, out.rows)) cancelled = true;
    return !cancelled;
  };

  auto work = [&](std::size_t i, unsigned worker) -> bool {
    double* row = out.values.data() + i * out.columns;
    std::fill(row, row + out.columns, kInf);
    const FrontSource source = FrontSource::vertex(sources[i]);
    if (stepwise) {
      std::unique_ptr<MinimalDistanceFront>& front = fronts[worker];
      if (!front) front = std::make_unique<MinimalDistanceFront>(mesh);
      std::size_t remaining = distinct_targets;
      if (targets) {
        front->set_settled_callback([&](VertexHandle v, double d, const Vec3&) {
          int j = first_column[static_cast<std::size_t>(v.idx())];
          if (j < 0 || row[j] != kInf) return;
          for (; j >= 0; j = next_column[static_cast<std::size_t>(j)]) row[j] = d;
          --remaining;
        });
      } else {
        front->set_settled_callback([row](VertexHandle v, double d, const Vec3&) {
          double& slot = row[v.idx()];
          if (slot == kInf) slot = d;  // as geodesic_distance: the first value stays
        });
      }
      front->reset(source, o);
      DistanceStop stop = DistanceStop::NotStarted;
      if (targets) {
        while (remaining > 0 && front->step()) {
        }
        stop = remaining == 0 ? DistanceStop::TargetReached : front->stop_reason();
      } else {
        stop = front->run();
      }
      front->set_settled_callback({});
      worker_peak[worker] = std::max(worker_peak[worker], front->peak_working_memory_bytes());
      return row_done(i, stop);
    }
    const DistanceField field = table ? (o.method == DistanceMethod::Fast ? geodesic_distance(mesh, *table, source, o)
                                                                           : dijkstra_distance(mesh, *table, source, o))
                                      : geodesic_distance(mesh, source, o);
    EF_CHECK(field.distance.size() == n, "a batch field does not have one value per vertex");
    if (targets) {
      for (std::size_t j = 0; j < out.columns; ++j) row[j] = field.distance[static_cast<std::size_t>((*targets)[j].idx())];
    } else {
      std::copy(field.distance.begin(), field.distance.end(), row);
    }
    const std::size_t temporary = field.distance.capacity() * sizeof(double) + field.order.capacity() * sizeof(VertexHandle);
    worker_peak[worker] = std::max(worker_peak[worker], field.peak_working_memory_bytes + temporary);
    return row_done(i, field.stop);
  };

  const bool complete = parallel_items(out.rows, out.threads, work);
  for (std::size_t i = 0; i < out.rows; ++i) {
    if (!out.computed[i]) std::fill(out.values.begin() + static_cast<std::ptrdiff_t>(i * out.columns),
                                    out.values.begin() + static_cast<std::ptrdiff_t>((i + 1) * out.columns), kNaN);
  }
  out.status = complete && done == out.rows ? BatchStatus::Complete : BatchStatus::Cancelled;
  for (const std::size_t p : worker_peak) out.peak_working_memory_bytes += p;
  return out;
}

}  // namespace

DistanceMatrix geodesic_distances(const Mesh& mesh, std::span<const VertexHandle> sources,
                                  const DistanceOptions& options, const BatchOptions& batch) {
  return run_batch(mesh, sources, nullptr, options, batch);
}

DistanceMatrix geodesic_distances(const Mesh& mesh, std::span<const VertexHandle> sources,
                                  std::span<const VertexHandle> targets, const DistanceOptions& options,
                                  const BatchOptions& batch) {
  const std::vector<VertexHandle> t(targets.begin(), targets.end());
  return run_batch(mesh, sources, &t, options, batch);
}

DistanceMatrix geodesic_distances(const GeodesicSolver& solver, std::span<const int> sources,
                                  std::span<const int> targets, const ArrayBatchOptions& options,
                                  const BatchOptions& batch) {
  const ArrayMesh& a = solver.converted();
  const std::size_t n_in = solver.n_vertices();
  auto vertex = [&](int v, const char* what) {
    if (v < 0 || static_cast<std::size_t>(v) >= n_in) {
      throw InvalidInput(std::string("geodesic_distances: ") + what + " vertex " + std::to_string(v) +
                         " is outside [0, " + std::to_string(n_in) + ")");
    }
    return VertexHandle(v);
  };
  std::vector<VertexHandle> src;
  src.reserve(sources.size());
  for (const int v : sources) src.push_back(vertex(v, "source"));
  // Mesh columns: each requested input vertex, then the copies of pinched ones; folded back below.
  std::vector<VertexHandle> cols;
  std::vector<std::size_t> column_of;  // per mesh column: the output column
  const std::size_t wanted = targets.empty() ? n_in : targets.size();
  for (std::size_t j = 0; j < wanted; ++j) {
    const VertexHandle v = targets.empty() ? VertexHandle(static_cast<int>(j)) : vertex(targets[j], "target");
    cols.push_back(v);
    column_of.push_back(j);
  }
  for (std::size_t j = 0; j < wanted; ++j) {
    for (const VertexHandle t : twins_of(a.mesh, cols[j])) {
      cols.push_back(t);
      column_of.push_back(j);
    }
  }
  DistanceOptions o;
  o.method = options.method;
  o.max_distance = options.max_distance;
  o.directions = false;
  DistanceMatrix m = targets.empty() && cols.size() == a.mesh.n_vertices() && n_in == cols.size()
                         ? geodesic_distances(a.mesh, src, o, batch)
                         : geodesic_distances(a.mesh, src, cols, o, batch);
  if (m.columns == wanted) return m;
  // A pinched vertex's column takes the smallest of its copies' values.
  std::vector<double> folded(m.rows * wanted, kNaN);
  for (std::size_t i = 0; i < m.rows; ++i) {
    if (!m.computed[i]) continue;
    double* row = folded.data() + i * wanted;
    std::fill(row, row + wanted, kInf);
    for (std::size_t c = 0; c < m.columns; ++c) row[column_of[c]] = std::min(row[column_of[c]], m(i, c));
  }
  m.values = std::move(folded);
  m.columns = wanted;
  return m;
}

}  // namespace edgefront
