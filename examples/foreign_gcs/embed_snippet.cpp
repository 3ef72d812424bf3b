// The README's "embed the twist repair in a host" snippet, compiled and run (ctest
// foreign_gcs.embed_snippet). `embed` below is the snippet, verbatim; the rest sets up a host (an
// icosphere as plain arrays whose refinement turns patches over, as a GCS loop's folds do) and
// checks the outcome: the host's arrays after the replays are the session's mirror face for face,
// and the turned patches are repaired (the share of area facing outward, against the same host
// steps without the repair).

#include <array>
#include <cmath>
#include <cstdio>
#include <functional>
#include <random>
#include <vector>

#include "shapes/shapes.h"  // only to make the test host's sphere
#include "twist/arrays.h"
#include "twist/repair_session.h"

namespace {

struct Changes {
  std::vector<int> moved, faces, removed;
};
using Refine = std::function<Changes(std::vector<double>&, std::vector<int>&)>;

// ---- the snippet ------------------------------------------------------------------------------
void embed(std::vector<double>& V, std::vector<int>& F, const twist::ReferenceNormals& reference, int batches,
           const Refine& host_refine) {
  twist::SessionOptions options;
  options.repair.detect.reference = &reference;          // the host's oriented points (optional)
  twist::RepairSession session(V, F, options);           // converts once
  twist::apply(session.initial_record(), V, F);          // pinched vertices split, if any
  for (int batch = 0; batch < batches; ++batch) {
    const Changes c = host_refine(V, F);                 // the host's own steps
    for (int v : c.moved) session.set_vertex(v, {V[3 * v], V[3 * v + 1], V[3 * v + 2]});
    for (int f : c.faces) session.set_face(f, {F[3 * f], F[3 * f + 1], F[3 * f + 2]});
    for (int f : c.removed) session.remove_face(f);
    twist::apply(session.repair(), V, F);                // cuts and flips, replayed on the host
  }
  twist::apply(session.finish(), V, F);                  // all of it, globally oriented
  twist::compact_faces(F);                               // drop the removed face slots
}
// ---- end of the snippet -----------------------------------------------------------------------

/// The host's refinement step: turns the patch within `radius` of a random vertex over (a rotation
/// by pi about a tangent axis through its centroid), as a refinement loop's fold does.
Changes turn_patch(std::vector<double>& V, const std::vector<int>& F, std::mt19937& rng, double radius) {
  const int n = static_cast<int>(V.size() / 3);
  std::vector<char> used(static_cast<size_t>(n), 0);
  for (int v : F)
    if (v >= 0) used[static_cast<size_t>(v)] = 1;
  int c = 0;
  do c = std::uniform_int_distribution<int>(0, n - 1)(rng); while (!used[static_cast<size_t>(c)]);
  const std::array<double, 3> p{V[3 * c], V[3 * c + 1], V[3 * c + 2]};
  Changes ch;
  std::array<double, 3> m{0, 0, 0};
  for (int v = 0; v < n; ++v) {
    double d2 = 0;
    for (int k = 0; k < 3; ++k) d2 += (V[3 * v + k] - p[k]) * (V[3 * v + k] - p[k]);
    if (!used[static_cast<size_t>(v)] || d2 > radius * radius) continue;
    ch.moved.push_back(v);
    for (int k = 0; k < 3; ++k) m[static_cast<size_t>(k)] += V[3 * v + k];
  }
  for (double& x : m) x /= static_cast<double>(ch.moved.size());
  // A unit axis orthogonal to the patch's normal direction (p, on a unit sphere about the origin).
  const double l = std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
  const std::array<double, 3> nn{p[0] / l, p[1] / l, p[2] / l};
  std::array<double, 3> a = std::abs(nn[0]) < 0.9 ? std::array<double, 3>{1, 0, 0} : std::array<double, 3>{0, 1, 0};
  const double an = a[0] * nn[0] + a[1] * nn[1] + a[2] * nn[2];
  for (size_t k = 0; k < 3; ++k) a[k] -= an * nn[k];
  const double al = std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
  for (double& x : a) x /= al;
  for (int v : ch.moved) {
    std::array<double, 3> d{};
    for (size_t k = 0; k < 3; ++k) d[k] = V[3 * static_cast<size_t>(v) + k] - m[k];
    const double along = d[0] * a[0] + d[1] * a[1] + d[2] * a[2];
    for (size_t k = 0; k < 3; ++k) V[3 * static_cast<size_t>(v) + k] = m[k] + 2 * along * a[k] - d[k];
  }
  return ch;
}

/// Area share of the live faces whose normal points away from the origin (the sphere's outside).
double outward_share(const std::vector<double>& V, const std::vector<int>& F) {
  double good = 0, all = 0;
  for (size_t f = 0; 3 * f < F.size(); ++f) {
    if (F[3 * f] < 0) continue;
    std::array<std::array<double, 3>, 3> p{};
    for (size_t c = 0; c < 3; ++c)
      for (size_t k = 0; k < 3; ++k) p[c][k] = V[3 * static_cast<size_t>(F[3 * f + c]) + k];
    const std::array<double, 3> e1{p[1][0] - p[0][0], p[1][1] - p[0][1], p[1][2] - p[0][2]};
    const std::array<double, 3> e2{p[2][0] - p[0][0], p[2][1] - p[0][1], p[2][2] - p[0][2]};
    const std::array<double, 3> n{e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
    const double area = 0.5 * std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    double side = 0;
    for (size_t k = 0; k < 3; ++k) side += n[k] * (p[0][k] + p[1][k] + p[2][k]);
    all += area;
    if (side > 0) good += area;
  }
  return all > 0 ? good / all : 0;
}

}  // namespace

int main() {
  const edgefront::MeshArrays sphere = edgefront::mesh_to_arrays(edgefront::shapes::icosphere(4));
  std::vector<double> normals = sphere.vertices;  // the unit sphere's outward normals
  const twist::ReferenceNormals reference = twist::reference_from_arrays(sphere.vertices, normals);
  const int batches = 3;
  const double radius = 0.25;

  // The same host steps without the repair.
  std::vector<double> V0 = sphere.vertices;
  std::vector<int> F0 = sphere.faces;
  std::mt19937 rng0(7);
  for (int b = 0; b < batches; ++b) turn_patch(V0, F0, rng0, radius);
  const double plain = outward_share(V0, F0);

  std::vector<double> V = sphere.vertices;
  std::vector<int> F = sphere.faces;
  std::mt19937 rng(7);
  embed(V, F, reference, batches, [&](std::vector<double>& v, std::vector<int>& f) { return turn_patch(v, f, rng, radius); });
  const double repaired = outward_share(V, F);

  // The replayed host is a valid mesh: the session built from it accepts it unchanged.
  twist::RepairSession check(V, F);
  const bool clean = check.initial_record().empty() && check.conversion().dropped_faces.empty();
  std::printf("embed-snippet: %zu -> %zu vertices, %zu -> %zu faces; outward area share: %.4f without the repair, %.4f with it; replayed host %s\n",
              sphere.n_vertices(), V.size() / 3, sphere.n_faces(), F.size() / 3, plain, repaired,
              clean ? "converts cleanly" : "does NOT convert cleanly");
  if (!clean || !(plain < 0.99) || !(repaired >= 0.99) || !(repaired > plain)) {
    std::fprintf(stderr, "embed-snippet: FAILED (expected: the turned patches lower the share below 0.99, the repair brings it to >= 0.99)\n");
    return 1;
  }
  return 0;
}
