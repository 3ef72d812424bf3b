// Batch geodesics (edgefront/batch_distance.h) and the thread loops (edgefront/parallel.h): every
// row equals the single-source field bit for bit, for every method and any thread count.

#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <limits>
#include <mutex>
#include <stdexcept>
#include <vector>

#include "edgefront/arrays.h"
#include "edgefront/batch_distance.h"
#include "edgefront/error.h"
#include "edgefront/mesh_io.h"
#include "edgefront/minimal_distance_front.h"
#include "edgefront/parallel.h"

namespace {

using edgefront::DistanceMatrix;
using edgefront::DistanceMethod;
using edgefront::DistanceOptions;
using edgefront::Mesh;
using edgefront::VertexHandle;

constexpr double kInf = std::numeric_limits<double>::infinity();
const DistanceMethod kMethods[] = {DistanceMethod::Mdf, DistanceMethod::Windows, DistanceMethod::Fast,
                                   DistanceMethod::Dijkstra};

const Mesh& bumpy() {
  static const Mesh mesh =
      edgefront::read_mesh((std::filesystem::path(EDGEFRONT_DATA_DIR) / "bumpy-sphere.off").string()).mesh;
  return mesh;
}

std::vector<VertexHandle> spread_vertices(const Mesh& mesh, size_t count) {
  std::vector<VertexHandle> out;
  for (size_t i = 0; i < count; ++i) out.emplace_back(static_cast<int>(i * mesh.n_vertices() / count));
  return out;
}

bool same_bytes(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

TEST(ParallelFor, ChunksCoverEveryItemOnceInContiguousOrder) {
  for (unsigned threads : {1u, 2u, 3u, 7u}) {
    std::vector<int> hits(100, 0);
    std::vector<std::pair<size_t, size_t>> chunks(threads, {0, 0});
    edgefront::parallel_for(hits.size(), threads, [&](size_t begin, size_t end, unsigned chunk) {
      chunks[chunk] = {begin, end};
      for (size_t i = begin; i < end; ++i) ++hits[i];
    });
    for (int h : hits) EXPECT_EQ(h, 1) << threads << " threads";
    EXPECT_EQ(chunks.front().first, 0u);
    EXPECT_EQ(chunks.back().second, hits.size());
    for (size_t c = 1; c < chunks.size(); ++c) EXPECT_EQ(chunks[c].first, chunks[c - 1].second);
  }
  EXPECT_EQ(edgefront::threads_for(3, 8), 3u);
  EXPECT_EQ(edgefront::threads_for(0, 8), 1u);
  EXPECT_GE(edgefront::threads_for(1000, 0), 1u);
  EXPECT_EQ(edgefront::resolve_threads(0), edgefront::default_threads());
}

TEST(ParallelFor, RethrowsTheLowestChunksException) {
  EXPECT_THROW(edgefront::parallel_for(10, 3,
                                       [](size_t begin, size_t, unsigned chunk) {
                                         if (chunk >= 1) throw std::runtime_error("chunk " + std::to_string(begin));
                                       }),
               std::runtime_error);
  try {
    edgefront::parallel_for(9, 3, [](size_t begin, size_t, unsigned chunk) {
      if (chunk >= 1) throw std::runtime_error("chunk at " + std::to_string(begin));
    });
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(), "chunk at 3");
  }
}

TEST(ParallelItems, RunsEveryItemOnceAndStopsWhenAsked) {
  std::vector<std::atomic<int>> hits(50);
  EXPECT_TRUE(edgefront::parallel_items(hits.size(), 3, [&](size_t i, unsigned) {
    ++hits[i];
    return true;
  }));
  for (const auto& h : hits) EXPECT_EQ(h.load(), 1);
  std::atomic<int> ran{0};
  EXPECT_FALSE(edgefront::parallel_items(1000, 2, [&](size_t, unsigned) { return ++ran < 5; }));
  EXPECT_LT(ran.load(), 1000);
}

TEST(BatchDistance, EveryRowIsTheSingleSourceFieldBitForBit) {
  const Mesh& mesh = bumpy();
  const std::vector<VertexHandle> sources = spread_vertices(mesh, 5);
  for (DistanceMethod method : kMethods) {
    DistanceOptions o;
    o.method = method;
    const DistanceMatrix m = edgefront::geodesic_distances(mesh, sources, o, {.threads = 2});
    ASSERT_EQ(m.rows, sources.size());
    ASSERT_EQ(m.columns, mesh.n_vertices());
    EXPECT_EQ(m.status, edgefront::BatchStatus::Complete);
    EXPECT_EQ(m.threads, 2u);
    EXPECT_GT(m.peak_working_memory_bytes, 0u);
    for (size_t i = 0; i < sources.size(); ++i) {
      const edgefront::DistanceField f = edgefront::geodesic_distance(mesh, edgefront::FrontSource::vertex(sources[i]), o);
      const std::vector<double> row(m.row(i).begin(), m.row(i).end());
      EXPECT_TRUE(same_bytes(row, f.distance)) << edgefront::to_string(method) << " row " << i;
      EXPECT_EQ(m.stop[i], f.stop);
      EXPECT_EQ(m.computed[i], 1);
      EXPECT_EQ(row[static_cast<size_t>(sources[i].idx())], 0.0);
    }
  }
}

TEST(BatchDistance, SameBytesForOneTwoAndThreeThreads) {
  const Mesh& mesh = bumpy();
  const std::vector<VertexHandle> sources = spread_vertices(mesh, 7);
  const std::vector<VertexHandle> targets = spread_vertices(mesh, 40);
  for (DistanceMethod method : kMethods) {
    DistanceOptions o;
    o.method = method;
    o.max_distance = 1.5;
    const DistanceMatrix one = edgefront::geodesic_distances(mesh, sources, o, {.threads = 1});
    const DistanceMatrix one_matrix = edgefront::geodesic_distances(mesh, sources, targets, o, {.threads = 1});
    EXPECT_EQ(one.threads, 1u);
    for (unsigned threads : {2u, 3u}) {
      const DistanceMatrix m = edgefront::geodesic_distances(mesh, sources, o, {.threads = threads});
      EXPECT_EQ(m.threads, threads);
      EXPECT_TRUE(same_bytes(m.values, one.values)) << edgefront::to_string(method) << ", " << threads << " threads";
      const DistanceMatrix t = edgefront::geodesic_distances(mesh, sources, targets, o, {.threads = threads});
      EXPECT_TRUE(same_bytes(t.values, one_matrix.values)) << edgefront::to_string(method) << ", " << threads;
    }
  }
}

TEST(BatchDistance, MatrixBetweenVertexSetsReadsTheFieldsAtTheTargets) {
  const Mesh& mesh = bumpy();
  const std::vector<VertexHandle> sources = spread_vertices(mesh, 4);
  // Targets repeat a vertex and include a source: each column is read from the full field.
  std::vector<VertexHandle> targets = spread_vertices(mesh, 9);
  targets.push_back(targets[2]);
  targets.push_back(sources[1]);
  for (DistanceMethod method : kMethods) {
    for (double bound : {kInf, 0.8}) {
      DistanceOptions o;
      o.method = method;
      o.max_distance = bound;
      const DistanceMatrix full = edgefront::geodesic_distances(mesh, sources, o, {.threads = 2});
      const DistanceMatrix m = edgefront::geodesic_distances(mesh, sources, targets, o, {.threads = 2});
      ASSERT_EQ(m.rows, sources.size());
      ASSERT_EQ(m.columns, targets.size());
      size_t beyond = 0;
      for (size_t i = 0; i < m.rows; ++i) {
        for (size_t j = 0; j < m.columns; ++j) {
          const double want = full(i, static_cast<size_t>(targets[j].idx()));
          EXPECT_EQ(std::memcmp(&want, &m.values[i * m.columns + j], sizeof(double)), 0)
              << edgefront::to_string(method) << " bound " << bound << " at " << i << "," << j;
          beyond += std::isinf(m(i, j));
        }
        EXPECT_EQ(m(i, m.columns - 1) == 0.0, i == 1);
      }
      if (bound < kInf) {
        EXPECT_GT(beyond, 0u) << "the bound left every target reachable: test too weak";
      } else {
        EXPECT_EQ(beyond, 0u);
      }
    }
  }
}

TEST(BatchDistance, ProgressCountsRowsAndCancelGivesAPartialResult) {
  const Mesh& mesh = bumpy();
  const std::vector<VertexHandle> sources = spread_vertices(mesh, 8);
  std::mutex m;
  std::vector<size_t> seen;
  const DistanceMatrix all = edgefront::geodesic_distances(
      mesh, sources, {}, {.threads = 2, .progress = [&](size_t done, size_t total) {
                            const std::lock_guard<std::mutex> lock(m);
                            EXPECT_EQ(total, 8u);
                            seen.push_back(done);
                            return true;
                          }});
  ASSERT_EQ(seen.size(), 8u);
  for (size_t k = 0; k < seen.size(); ++k) EXPECT_EQ(seen[k], k + 1);
  EXPECT_EQ(all.status, edgefront::BatchStatus::Complete);

  const DistanceMatrix part = edgefront::geodesic_distances(
      mesh, sources, {}, {.threads = 1, .progress = [](size_t done, size_t) { return done < 3; }});
  EXPECT_EQ(part.status, edgefront::BatchStatus::Cancelled);
  for (size_t i = 0; i < part.rows; ++i) {
    const bool computed = i < 3;  // one thread takes the rows in order
    EXPECT_EQ(part.computed[i], computed ? 1 : 0) << i;
    if (computed) {
      const std::vector<double> a(part.row(i).begin(), part.row(i).end()), b(all.row(i).begin(), all.row(i).end());
      EXPECT_TRUE(same_bytes(a, b));
    } else {
      EXPECT_TRUE(std::isnan(part(i, 0)));
      EXPECT_EQ(part.stop[i], edgefront::DistanceStop::NotStarted);
    }
  }
}

TEST(BatchDistance, BadInputIsAClearError) {
  const Mesh& mesh = bumpy();
  const std::vector<VertexHandle> none;
  const std::vector<VertexHandle> one{VertexHandle(0)};
  const std::vector<VertexHandle> outside{VertexHandle(0), VertexHandle(static_cast<int>(mesh.n_vertices()))};
  auto message = [&](auto&& call) -> std::string {
    try {
      call();
    } catch (const edgefront::InvalidInput& e) {
      return e.what();
    }
    return "no InvalidInput";
  };
  EXPECT_NE(message([&] { edgefront::geodesic_distances(mesh, none); }).find("no source"), std::string::npos);
  EXPECT_NE(message([&] { edgefront::geodesic_distances(mesh, outside); }).find("source 1"), std::string::npos);
  EXPECT_NE(message([&] { edgefront::geodesic_distances(mesh, one, outside); }).find("target 1"), std::string::npos);
  EXPECT_NE(message([&] { edgefront::geodesic_distances(mesh, one, none); }).find("no target"), std::string::npos);
  EXPECT_NE(message([&] { edgefront::geodesic_distances(mesh, one, {.max_distance = std::nan("")}); }).find("max_distance"),
            std::string::npos);
  EXPECT_NE(message([&] { edgefront::geodesic_distances(mesh, one, {.target = VertexHandle(1)}); }).find("target"),
            std::string::npos);
  // An absurd thread count (a typo, or -1 cast to unsigned) is refused before any thread starts.
  const std::vector<VertexHandle> two{VertexHandle(0), VertexHandle(1)};
  EXPECT_NE(message([&] { edgefront::geodesic_distances(mesh, two, {}, {.threads = 4097}); }).find("threads must be at most 4096"),
            std::string::npos);
  EXPECT_NE(message([&] { edgefront::geodesic_distances(mesh, two, {}, {.threads = static_cast<unsigned>(-1)}); })
                .find("threads must be at most"),
            std::string::npos);
}

TEST(BatchDistance, ArrayEntryPointMatchesTheSolverOnAPinchedMesh) {
  // The file as plain arrays (each pinched vertex once): the solver splits the pinches.
  std::ifstream in(std::filesystem::path(EDGEFRONT_TEST_DATA_DIR) / "pinched-body.off");
  std::string line, header;
  std::stringstream body;
  while (std::getline(in, line))
    if (!line.empty() && line[0] != '#') body << line << "\n";
  size_t nv = 0, nf = 0, ne = 0;
  body >> header >> nv >> nf >> ne;
  ASSERT_EQ(header, "OFF");
  std::vector<double> vertices(3 * nv);
  for (double& x : vertices) body >> x;
  std::vector<int> faces;
  for (size_t f = 0; f < nf; ++f) {
    int k = 0, a = 0, b = 0, c = 0;
    body >> k >> a >> b >> c;
    ASSERT_EQ(k, 3);
    faces.insert(faces.end(), {a, b, c});
  }
  ASSERT_TRUE(body) << "pinched-body.off did not parse";
  const edgefront::GeodesicSolver solver(vertices, faces);
  ASSERT_GT(solver.converted().report.vertex_copies, 0u) << "the test needs a pinched mesh";
  const std::vector<int> sources{0, 5, static_cast<int>(solver.n_vertices()) - 1};
  const std::vector<int> targets{3, 1, 3, 0};
  for (DistanceMethod method : kMethods) {
    const DistanceMatrix fields = edgefront::geodesic_distances(solver, sources, {}, {.method = method}, {.threads = 2});
    const DistanceMatrix m = edgefront::geodesic_distances(solver, sources, targets, {.method = method}, {.threads = 2});
    ASSERT_EQ(fields.columns, solver.n_vertices());
    ASSERT_EQ(m.columns, targets.size());
    for (size_t i = 0; i < sources.size(); ++i) {
      const std::vector<int> s{sources[i]};
      const edgefront::DistanceArrays d = solver.distance_from_vertices(s, {.method = method});
      const std::vector<double> row(fields.row(i).begin(), fields.row(i).end());
      EXPECT_TRUE(same_bytes(row, d.distance)) << edgefront::to_string(method) << " row " << i;
      for (size_t j = 0; j < targets.size(); ++j) EXPECT_EQ(m(i, j), d.distance[static_cast<size_t>(targets[j])]);
    }
  }
  const std::vector<int> bad{static_cast<int>(solver.n_vertices())};
  EXPECT_THROW(edgefront::geodesic_distances(solver, bad, {}), edgefront::InvalidInput);
}

}  // namespace
