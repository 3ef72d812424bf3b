// bench_normals: fitted normals of clouds without normals against the truth (not a test; prints a
// markdown table).
//
//   bench_normals [--k K] [--max-residual R] [--own] [--plane] [--points N] [--noise S] [--seed S]
//                 [--smooth] INPUT...
//
// INPUT is a mesh file (.off/.ply/.obj: its vertex set is the cloud, as gcs-reconstruct reads it;
// the truth is the mesh's area-weighted vertex normals), a point file with normals (the truth) or shape:NAME (shapes::sample with N
// points, default 10000, Gaussian noise along the normal of S point spacings, default 0, seed S;
// the truth is the exact normals) or sphere:FILE (a point file sampling a sphere, e.g. CGAL's
// sphere_20k.xyz: the truth points away from the points' centroid); --smooth smooths the points first (gcs::smooth_noise, as the
// reconstructor does to a noisy cloud) and keeps the truth's normals. For every input two estimates: "old" is the reconstructor's
// estimate before session 13 (gcsnormals): the plane through the 20 nearest points, NaN when its
// smallest eigenvalue is >= 5% of the middle one; "new" is gcs::fit_normals with the options given
// (--k neighbours, --max-residual, --own: best_neighbourhood off, --plane: quadric_normal off).
// Both are oriented by the reconstructor's orient_normals (gcs/src/detail/double_layer.h), the
// new ones with their fits' residuals as the noise.
// Columns: share of the points whose normal is within 30 degrees of the truth's line (unsigned),
// share NaN, share oriented wrong (defined and more than 90 degrees from the truth after the
// orientation), share within 30 degrees oriented, whether the orientation succeeded, time of the
// fit (CPU, this thread).

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <limits>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "../gcs/src/detail/double_layer.h"
#include "edgefront/mesh_io.h"
#include "edgefront/point_cloud_io.h"
#include "edgefront/point_index.h"
#include "shapes/shapes.h"
#include "gcs/cloud_noise.h"
#include "gcs/cloud_normals.h"
#include "bench_timing.h"

namespace {

using edgefront::PointIndex;
using edgefront::Vec3;

using efbench::cpu_seconds;

// The reconstructor's fit before gcsnormals (reconstructor.cpp point_normal at main 84332ad).
std::vector<Vec3> old_normals(const std::vector<Vec3>& pts, const PointIndex& index) {
  std::vector<Vec3> out(pts.size());
  std::vector<PointIndex::Neighbor> knn;
  for (size_t i = 0; i < pts.size(); ++i) {
    index.k_nearest(pts[i], 20, knn);
    Eigen::Vector3d c = Eigen::Vector3d::Zero();
    for (const auto& nb : knn) c += Eigen::Vector3d(pts[nb.index][0], pts[nb.index][1], pts[nb.index][2]);
    c /= static_cast<double>(knn.size());
    Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
    for (const auto& nb : knn) {
      const Eigen::Vector3d q = Eigen::Vector3d(pts[nb.index][0], pts[nb.index][1], pts[nb.index][2]) - c;
      cov += q * q.transpose();
    }
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);
    const Eigen::Vector3d e = eig.eigenvectors().col(0), ev = eig.eigenvalues();
    out[i] = ev[0] < 0.05 * ev[1] ? Vec3(e[0], e[1], e[2]) : Vec3(std::numeric_limits<double>::quiet_NaN(), 0, 0);
  }
  return out;
}

struct Truth {
  std::vector<Vec3> points, normals;
};

Truth from_mesh(const std::string& path) {
  Truth t;
  const edgefront::PointCloud cloud = edgefront::read_points(path);
  t.points = cloud.points;
  if (cloud.has_normals()) {  // a point file with normals: they are the truth
    for (const Vec3& m : cloud.normals) t.normals.push_back(m.normalized());
    return t;
  }
  const edgefront::Mesh mesh = edgefront::read_mesh(path).mesh;
  std::vector<Vec3> vp, vn;
  for (auto v : mesh.vertices()) {
    vp.push_back(mesh.point(v));
    vn.push_back(Vec3(0, 0, 0));
  }
  for (auto f : mesh.faces()) {
    std::vector<int> ids;
    for (auto v : mesh.fv_range(f)) ids.push_back(v.idx());
    const Vec3 a = vp[ids[0]], b = vp[ids[1]], c = vp[ids[2]];
    const Vec3 area2 = (b - a) % (c - a);  // area-weighted
    for (int id : ids) vn[id] += area2;
  }
  const PointIndex index(vp);
  for (const Vec3& p : t.points) {
    const auto nb = index.nearest(p);
    const double l = vn[nb.index].norm();
    t.normals.push_back(l > 0 ? vn[nb.index] / l : Vec3(0, 0, 0));
  }
  return t;
}

Truth from_shape(const std::string& name, size_t points, double noise_spacings, unsigned seed) {
  edgefront::shapes::SampleOptions o;
  o.points = points;
  o.seed = seed;
  edgefront::PointCloud c = edgefront::shapes::sample(name, o);
  if (noise_spacings > 0) {
    const PointIndex index(c.points);
    double sum = 0;
    std::vector<PointIndex::Neighbor> knn;
    for (const Vec3& p : c.points) {
      index.k_nearest(p, 2, knn);
      sum += std::sqrt(knn.back().distance2);
    }
    o.noise_sigma = noise_spacings * sum / static_cast<double>(c.size());
    c = edgefront::shapes::sample(name, o);
  }
  return {c.points, c.normals};
}

struct Score {
  double within = 0, nan = 0, wrong = 0, oriented_within = 0, seconds = 0, off60 = 0;
  bool oriented = false;
};

Score score(const Truth& t, const PointIndex& index, std::vector<Vec3> n, double seconds,
            const std::vector<double>* noise = nullptr) {
  Score s;
  s.seconds = seconds;
  const double cos30 = std::cos(M_PI / 6);
  const double m = static_cast<double>(t.points.size());
  for (size_t i = 0; i < n.size(); ++i) {
    if (!std::isfinite(n[i][0])) {
      s.nan += 1 / m;
      continue;
    }
    if (std::abs(n[i].normalized() | t.normals[i]) >= cos30) s.within += 1 / m;
    if (std::abs(n[i].normalized() | t.normals[i]) < 0.5) s.off60 += 1 / m;
  }
  s.oriented = gcs::detail::orient_normals(t.points, index, n, 8, noise);
  for (size_t i = 0; i < n.size(); ++i) {
    if (!std::isfinite(n[i][0])) continue;
    const double c = n[i].normalized() | t.normals[i];
    if (c < 0) s.wrong += 1 / m;
    if (c >= cos30) s.oriented_within += 1 / m;
  }
  return s;
}

}  // namespace

int main(int argc, char** argv) {
  gcs::NormalFitOptions fo;
  size_t points = 10000;
  double noise = 0;
  unsigned seed = 1;
  bool smooth = false;
  std::vector<std::string> inputs;
  for (int a = 1; a < argc; ++a) {
    const std::string s = argv[a];
    if (s == "--k" && a + 1 < argc) fo.neighbours = std::strtoul(argv[++a], nullptr, 10);
    else if (s == "--max-residual" && a + 1 < argc) fo.max_residual = std::atof(argv[++a]);
    else if (s == "--own") fo.best_neighbourhood = false;
    else if (s == "--plane") fo.quadric_normal = false;
    else if (s == "--points" && a + 1 < argc) points = std::strtoul(argv[++a], nullptr, 10);
    else if (s == "--noise" && a + 1 < argc) noise = std::atof(argv[++a]);
    else if (s == "--smooth") smooth = true;
    else if (s == "--seed" && a + 1 < argc) seed = static_cast<unsigned>(std::atoi(argv[++a]));
    else if (s.rfind("--", 0) == 0) {
      std::fprintf(stderr, "usage: bench_normals [--k K] [--max-residual R] [--own] [--plane] [--points N] [--noise S] [--seed S] INPUT...\n");
      return 2;
    } else inputs.push_back(s);
  }
  std::printf("| input (points) | old: within 30 deg / NaN / oriented wrong / oriented within 30 / orientable / s / more than 60 deg off | new (k %zu, max residual %.3g%s%s): same |\n|---|---|---|\n",
              fo.neighbours, fo.max_residual, fo.best_neighbourhood ? "" : ", own", fo.quadric_normal ? "" : ", plane");
  for (const std::string& in : inputs) {
    Truth t;
    if (in.rfind("shape:", 0) == 0) {
      t = from_shape(in.substr(6), points, noise, seed);
    } else if (in.rfind("sphere:", 0) == 0) {  // a point file sampling a sphere about its centroid
      t.points = edgefront::read_points(in.substr(7)).points;
      Vec3 c(0, 0, 0);
      for (const Vec3& p : t.points) c += p / static_cast<double>(t.points.size());
      for (const Vec3& p : t.points) t.normals.push_back((p - c).normalized());
    } else {
      t = from_mesh(in);
    }
    if (smooth) {  // as the reconstructor does to a noisy cloud (gcs::smooth_noise, default options)
      edgefront::PointCloud c;
      c.points = t.points;
      gcs::smooth_noise(c);
      t.points = c.points;
    }
    const PointIndex index(t.points);
    double t0 = cpu_seconds();
    std::vector<Vec3> a = old_normals(t.points, index);
    const double ta = cpu_seconds() - t0;
    t0 = cpu_seconds();
    std::vector<double> residuals;
    std::vector<Vec3> b = gcs::fit_normals(t.points, index, fo, &residuals);
    const double tb = cpu_seconds() - t0;
    const Score sa = score(t, index, a, ta), sb = score(t, index, b, tb, &residuals);
    std::string name = in.substr(in.find_last_of('/') + 1);
    if (noise > 0 && in.rfind("shape:", 0) == 0) name += " noise " + std::to_string(noise);
    std::printf("| %s (%zu) | %.3f / %.3f / %.3f / %.3f / %s / %.3f / %.3f | %.3f / %.3f / %.3f / %.3f / %s / %.3f / %.3f |\n",
                name.c_str(), t.points.size(), sa.within, sa.nan, sa.wrong, sa.oriented_within, sa.oriented ? "yes" : "no",
                sa.seconds, sa.off60, sb.within, sb.nan, sb.wrong, sb.oriented_within, sb.oriented ? "yes" : "no", sb.seconds,
                sb.off60);
    std::fflush(stdout);
  }
  return 0;
}
