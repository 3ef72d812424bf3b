// The evaluation as text (format_evaluation) and as JSON (evaluation_to_json).
#include <array>
#include <charconv>
#include <cmath>
#include <cstddef>
#include <iomanip>
#include <sstream>
#include <string>

#include "gcs/evaluation.h"

namespace gcs {

namespace {

std::string num(double v) {
  if (!std::isfinite(v)) return "null";
  std::array<char, 64> buf{};
  const auto r = std::to_chars(buf.data(), buf.data() + buf.size(), v);
  return std::string(buf.data(), r.ptr);
}

std::string fixed(double v, int digits) {
  std::ostringstream os;
  os << std::fixed << std::setprecision(digits) << v;
  return os.str();
}

std::string distance_json(const OneSidedDistance& d, double diag) {
  std::ostringstream os;
  os << "{\"count\": " << d.count << ", \"mean\": " << num(d.mean) << ", \"rms\": " << num(d.rms)
     << ", \"median\": " << num(d.median) << ", \"p95\": " << num(d.p95) << ", \"max\": " << num(d.max)
     << ", \"mean_percent\": " << num(100 * d.mean / diag) << ", \"p95_percent\": " << num(100 * d.p95 / diag)
     << ", \"max_percent\": " << num(100 * d.max / diag) << "}";
  return os.str();
}

}  // namespace

std::string format_evaluation(const Evaluation& e) {
  std::ostringstream os;
  auto dist = [&](const char* label, double v) {
    os << label << fixed(v, 6) << "  (" << fixed(e.scale(v), 4) << "% of bbox diagonal)\n";
  };
  os << "ground truth:            " << (e.ground_truth_is_mesh ? "mesh, " : "point set, ")
     << e.ground_truth_points << (e.ground_truth_is_mesh ? " samples" : " points") << ", bbox diagonal "
     << fixed(e.gt_bbox_diagonal, 6) << "\n";
  os << "result samples:          " << e.result_to_gt.count << "; distance to a mesh: "
     << (e.exact_surface_distance ? "exact, to its surface" : "to its nearest sample") << "\n";
  dist("chamfer-L1:              ", e.chamfer_l1);
  dist("  result -> gt mean:     ", e.result_to_gt.mean);
  dist("  gt -> result mean:     ", e.gt_to_result.mean);
  dist("hausdorff:               ", e.hausdorff);
  dist("  result -> gt max:      ", e.result_to_gt.max);
  dist("  gt -> result max:      ", e.gt_to_result.max);
  dist("hausdorff 95%:           ", e.hausdorff_p95);
  for (const FScore& f : e.fscores) {
    os << "F-score @ " << fixed(100 * f.threshold_fraction, 2) << "%:          " << fixed(f.fscore, 4)
       << "  (precision " << fixed(f.precision, 4) << ", recall " << fixed(f.recall, 4) << ", threshold "
       << fixed(f.threshold, 6) << ")\n";
  }
  if (e.normal_consistency) {
    os << "normal consistency:      " << fixed(*e.normal_consistency, 4) << "  (mean |n.n_gt|)\n";
  } else {
    os << "normal consistency:      n/a (ground truth without normals)\n";
  }
  if (e.orientation) {
    std::size_t with_samples = 0, flipped = 0;
    for (const auto& c : e.orientation->components) {
      with_samples += c.samples > 0 ? 1 : 0;
      flipped += c.samples > 0 && c.flipped ? 1 : 0;
    }
    os << "orientation consistency: " << fixed(e.orientation->raw, 4) << " as is, "
       << fixed(e.orientation->per_component, 4) << " with the better sign per component (" << flipped
       << " of " << with_samples << " components better flipped)\n";
  } else {
    os << "orientation consistency: n/a (ground truth without normals)\n";
  }
  const MeshValidity& m = e.validity;
  os << "mesh:                    " << m.vertices << " vertices, " << m.edges << " edges, " << m.faces
     << " faces, area " << fixed(m.area, 6) << "\n";
  os << "manifold:                edges " << (m.edge_manifold ? "yes" : "no") << ", vertices "
     << (m.vertex_manifold ? "yes" : "no") << " (" << m.nonmanifold_vertices << " non-manifold)";
  if (m.faces_dropped_when_read > 0) {
    os << "; but the file had " << m.faces_dropped_when_read
       << " more faces that made it non-manifold (dropped on reading)";
  }
  os << "\n";
  os << "components:              " << m.components << ", border loops " << m.border_loops
     << (m.closed ? " (closed)" : "") << ", isolated vertices " << m.isolated_vertices << "\n";
  os << "euler / genus:           " << m.euler_characteristic << " / " << m.genus;
  if (m.component_genus.size() > 1) {
    os << "  (per component:";
    for (std::size_t i = 0; i < m.component_genus.size() && i < 10; ++i) os << " " << m.component_genus[i];
    if (m.component_genus.size() > 10) os << " ...";
    os << ")";
  }
  os << "\n";
  os << "self-intersecting pairs: "
     << (m.self_intersecting_pairs ? std::to_string(*m.self_intersecting_pairs) : std::string("not computed"))
     << "\n";
  os << "degenerate / duplicate:  " << m.degenerate_faces << " / " << m.duplicate_faces << " faces\n";
  os << "min angle:               " << fixed(m.min_angle_deg, 2) << " deg, median of per-face minimum "
     << fixed(m.median_min_angle_deg, 2) << " deg; " << fixed(100 * m.faces_min_angle_below_10, 2)
     << "% of faces < 10 deg, " << fixed(100 * m.faces_min_angle_below_30, 2) << "% < 30 deg\n";
  os << "valence histogram:      ";
  std::size_t total = 0;
  for (const std::size_t c : m.valence_histogram) total += c;
  for (std::size_t k = 0; k < m.valence_histogram.size(); ++k) {
    if (m.valence_histogram[k] == 0) continue;
    os << " " << k << ":" << m.valence_histogram[k] << " ("
       << fixed(100.0 * static_cast<double>(m.valence_histogram[k]) / static_cast<double>(total), 1) << "%)";
  }
  os << "\n";
  return os.str();
}

std::string evaluation_to_json(const Evaluation& e) {
  std::ostringstream os;
  const double diag = e.gt_bbox_diagonal;
  os << "{\"ground_truth\": {\"kind\": \"" << (e.ground_truth_is_mesh ? "mesh" : "points")
     << "\", \"points\": " << e.ground_truth_points << ", \"bbox_diagonal\": " << num(diag) << "},\n";
  os << " \"result_samples\": " << e.result_to_gt.count << ", \"distance_to_mesh\": \""
     << (e.exact_surface_distance ? "surface" : "nearest_sample") << "\",\n";
  os << " \"chamfer_l1\": " << num(e.chamfer_l1) << ", \"chamfer_l1_percent\": " << num(e.scale(e.chamfer_l1))
     << ",\n";
  os << " \"hausdorff\": " << num(e.hausdorff) << ", \"hausdorff_percent\": " << num(e.scale(e.hausdorff))
     << ",\n";
  os << " \"hausdorff_p95\": " << num(e.hausdorff_p95)
     << ", \"hausdorff_p95_percent\": " << num(e.scale(e.hausdorff_p95)) << ",\n";
  os << " \"result_to_gt\": " << distance_json(e.result_to_gt, diag) << ",\n";
  os << " \"gt_to_result\": " << distance_json(e.gt_to_result, diag) << ",\n";
  os << " \"fscores\": [";
  for (std::size_t i = 0; i < e.fscores.size(); ++i) {
    const FScore& f = e.fscores[i];
    os << (i ? ", " : "") << "{\"threshold_fraction\": " << num(f.threshold_fraction)
       << ", \"threshold\": " << num(f.threshold) << ", \"precision\": " << num(f.precision)
       << ", \"recall\": " << num(f.recall) << ", \"fscore\": " << num(f.fscore) << "}";
  }
  os << "],\n";
  os << " \"normal_consistency\": " << (e.normal_consistency ? num(*e.normal_consistency) : "null") << ",\n";
  os << " \"orientation_consistency\": ";
  if (e.orientation) {
    os << "{\"raw\": " << num(e.orientation->raw)
       << ", \"per_component\": " << num(e.orientation->per_component) << ", \"components\": [";
    bool first = true;
    for (std::size_t c = 0; c < e.orientation->components.size(); ++c) {
      const ComponentOrientation& co = e.orientation->components[c];
      if (co.faces == 0) continue;
      os << (first ? "" : ", ") << "{\"component\": " << c << ", \"faces\": " << co.faces
         << ", \"samples\": " << co.samples << ", \"area_share\": " << num(co.area_share)
         << ", \"agreeing\": " << num(co.agreeing) << ", \"flipped\": " << (co.flipped ? "true" : "false")
         << "}";
      first = false;
    }
    os << "]}";
  } else {
    os << "null";
  }
  os << ",\n";
  const MeshValidity& m = e.validity;
  os << " \"mesh\": {\"vertices\": " << m.vertices << ", \"edges\": " << m.edges << ", \"faces\": " << m.faces
     << ", \"area\": " << num(m.area) << ", \"edge_manifold\": " << (m.edge_manifold ? "true" : "false")
     << ", \"nonmanifold_edges\": " << m.nonmanifold_edges
     << ", \"vertex_manifold\": " << (m.vertex_manifold ? "true" : "false")
     << ", \"nonmanifold_vertices\": " << m.nonmanifold_vertices
     << ", \"faces_dropped_when_read\": " << m.faces_dropped_when_read
     << ",\n  \"components\": " << m.components << ", \"border_loops\": " << m.border_loops
     << ", \"closed\": " << (m.closed ? "true" : "false")
     << ", \"euler_characteristic\": " << m.euler_characteristic << ", \"genus\": " << num(m.genus)
     << ", \"component_genus\": [";
  for (std::size_t i = 0; i < m.component_genus.size(); ++i)
    os << (i ? ", " : "") << num(m.component_genus[i]);
  os << "],\n  \"isolated_vertices\": " << m.isolated_vertices
     << ", \"degenerate_faces\": " << m.degenerate_faces << ", \"duplicate_faces\": " << m.duplicate_faces
     << ", \"self_intersecting_pairs\": "
     << (m.self_intersecting_pairs ? std::to_string(*m.self_intersecting_pairs) : std::string("null"))
     << ",\n  \"min_angle_deg\": " << num(m.min_angle_deg)
     << ", \"median_min_angle_deg\": " << num(m.median_min_angle_deg)
     << ", \"faces_min_angle_below_10\": " << num(m.faces_min_angle_below_10)
     << ", \"faces_min_angle_below_30\": " << num(m.faces_min_angle_below_30) << ", \"valence_histogram\": [";
  for (std::size_t k = 0; k < m.valence_histogram.size(); ++k)
    os << (k ? ", " : "") << m.valence_histogram[k];
  os << "]}}\n";
  return os.str();
}

}  // namespace gcs
