#include "detail/border_rejoin.h"

namespace gcs::detail {

RejoinResult rejoin_borders(edgefront::Mesh& mesh, const CloudQuery& cloud, const RejoinParams& params) {
  RejoinResult r;
  if (!(params.mean_edge_length > 0) || !(params.max_support_distance > 0) || !(params.max_gap_edges > 0)) return r;
  ZipParams zp;
  zp.mean_edge_length = params.mean_edge_length;
  zp.max_support_distance = params.max_support_distance;
  zp.max_gap_edges = params.max_gap_edges;
  zp.max_zips = params.max_zips;
  zp.across_loops = true;
  r.strips = zip_border_slits(mesh, cloud, zp);
  MergeParams mp;
  mp.mean_edge_length = params.mean_edge_length;
  mp.max_support_distance = params.max_support_distance;
  r.loops_merged = merge_border_loops(mesh, cloud, mp);
  return r;
}

}  // namespace gcs::detail
