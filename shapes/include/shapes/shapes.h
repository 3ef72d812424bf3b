#pragma once
/// \file shapes.h
/// Analytic test shapes: triangle meshes at a requested resolution, and area-uniform oriented
/// point samples with exact analytic normals. They are the inputs of the tests, benchmarks and
/// examples (see `/work/shared/notes/gcs-and-twist.md` §4 for why these shapes: thin shells,
/// open sheets and twisted strips are what provoke twisted GCS reconstructions).
///
/// Conventions, for every shape:
/// - Meshes are manifold and consistently oriented; closed shapes have outward normals (positive
///   signed volume). Vertices lie exactly on the analytic surface (up to rounding) and come in a
///   deterministic order (the order they are generated in; no hashing order leaks out).
/// - Samples are distributed uniformly by area over the whole surface (every patch, feet and end
///   caps included), with the exact analytic unit normal of the surface point (before noise).
///   On a crease (a vault's groin, a box edge) the normal of one of the adjacent patches is used;
///   creases have zero area, so this never matters in practice.
/// - Randomness only through seeds, drawn from `std::mt19937_64` with our own uniform and
///   Box-Muller normal transforms (not `std::uniform_real_distribution` /
///   `std::normal_distribution`, whose output differs between standard libraries), so a seed
///   gives the same points on every standard library; the last bits may still differ between
///   `libm` implementations of sin/cos/log.
/// - Invalid options (non-finite or non-positive sizes, resolution out of range, thickness not
///   smaller than the radius, ...) throw `edgefront::InvalidInput` with a message naming the shape
///   and the option.
///
/// Shapes (the names accepted by `make` and `sample`; `shape_names()` lists them):
///
/// | name             | surface                                                         | topology of the mesh |
/// |------------------|-----------------------------------------------------------------|----------------------|
/// | grid             | plane z = 0, outline/variant from `ShapeParams`                  | disk, 1 border       |
/// | grid-jittered    | square grid, interior vertices jittered                          | disk, 1 border       |
/// | grid-anisotropic | square grid of 1:`anisotropy` cells                              | disk, 1 border       |
/// | disk             | disk outline (concentric rings)                                  | disk, 1 border       |
/// | l-shape          | square minus its (+x, +y) quadrant                               | disk, 1 border       |
/// | icosphere        | sphere, subdivided icosahedron                                   | chi 2                |
/// | uv-sphere        | sphere, latitude/longitude rings                                 | chi 2                |
/// | hemisphere       | upper half sphere z >= 0, open                                   | disk, 1 border       |
/// | nested-spheres   | boundary of a hollow ball: outer sphere out, inner sphere in     | 2 spheres            |
/// | bumpy-sphere     | r(u) = R (1 + a sin(f ux) sin(f uy) sin(f uz)), star-shaped       | chi 2                |
/// | cylinder         | open cylinder x²+y² = R², 0 <= z <= length                        | annulus, 2 borders   |
/// | cone             | base radius R at z = 0 (open), apex (0,0,length) a vertex          | disk, 1 border       |
/// | torus            | major radius R (around z), tube radius r                          | chi 0                |
/// | double-torus     | tori at x = -R and x = +R, each cut at x = 0 and glued (a crease)  | chi -2 (genus 2)     |
/// | mobius           | Möbius strip, centre circle radius R, width w                     | see `mobius_strip`   |
/// | ribbon           | strip of length L, width w, half a twist about the x axis         | disk, 1 border       |
/// | vault-shell      | closed barrel vault shell: extrados R+t, intrados R, feet, caps   | chi 2                |
/// | vault-sheet      | extrados only: half cylinder radius R, open                        | disk, 1 border       |
/// | pointed-vault    | gothic (equilateral) arch sheet, span 2R, open                     | disk, 1 border       |
/// | groin-vault      | two crossing barrel sheets of radius R over a 2R square, open      | disk, 1 border       |
/// | thin-plate       | closed box [-R,R]² x [-t/2, t/2]                                   | chi 2                |
/// | hairpin          | closed thin wall of thickness t bent into a U, gap between arms    | chi 2                |
/// | landscape        | smooth seeded heightfield z = h(x, y) over [-R,R]²                 | disk, 1 border       |
/// | neck             | two blobs joined through a 3-vertex minimum pathway (mesh only)    | chi 2                |
///
/// Axes: cylinder, cone, tori, spheres around z; vaults along y (x across the span, z up);
/// the hairpin's arms run along +x, stacked in z, width along y.

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "edgefront/mesh.h"
#include "edgefront/point_cloud.h"

namespace edgefront::shapes {

/// How the vertices of a planar grid are placed.
enum class GridVariant {
  regular,     ///< regular cells
  jittered,    ///< interior vertices displaced at random (seeded); the outline stays exact
  anisotropic  ///< cells `anisotropy` times longer in y than in x (square and L outlines only)
};

/// Outline of a planar grid.
enum class GridOutline {
  square,  ///< [-half_size, half_size]²
  disk,    ///< disk of radius half_size, meshed by concentric rings (6k vertices on ring k)
  l_shape  ///< the square minus its open quadrant x > 0, y > 0
};

/// Options of `grid`.
struct GridOptions {
  int cells = 16;                              ///< cells along y (square, L; even for L) or rings (disk); in [1, 4096]
  double half_size = 1.0;                      ///< half side of the square / radius of the disk, > 0
  GridVariant variant = GridVariant::regular;  ///< vertex placement
  GridOutline outline = GridOutline::square;   ///< outline
  double jitter = 0.15;                        ///< jittered: max displacement per axis in cell sizes, in [0, 1/6) (no flips)
  double anisotropy = 20.0;                    ///< anisotropic: cell aspect ratio (x cells = cells * anisotropy), in [1, 1000]
  std::uint64_t seed = 1;                      ///< jittered: seed of the displacements; any value
};

/// Planar grid in z = 0, normals +z. \throws InvalidInput on bad options.
Mesh grid(const GridOptions& options = {});

/// Icosahedron subdivided `subdivisions` times (each time every triangle into 4), vertices
/// projected to the sphere. 20·4^s faces. \pre 0 <= subdivisions <= 8. \throws InvalidInput
Mesh icosphere(int subdivisions, double radius = 1.0);

/// Latitude/longitude sphere: `around` segments in longitude (>= 3), `rings` in latitude (>= 2);
/// one vertex at each pole. \throws InvalidInput
Mesh uv_sphere(int around, int rings, double radius = 1.0);

/// Open upper hemisphere z >= 0 (one border loop, the equator). \throws InvalidInput
Mesh hemisphere(int around, int rings, double radius = 1.0);

/// Two concentric icospheres bounding a hollow ball: the outer one (radius `outer_radius`)
/// oriented outward, the inner one (radius `inner_radius`) oriented toward the centre, so the
/// normals point out of the solid shell. Two components; outer vertices first.
/// \pre 0 < inner_radius < outer_radius. \throws InvalidInput
Mesh nested_spheres(int subdivisions, double outer_radius = 1.0, double inner_radius = 0.5);

/// Star-shaped bumpy sphere r(u) = radius·(1 + amplitude·sin(f·ux)·sin(f·uy)·sin(f·uz)), f =
/// `frequency`, meshed as a displaced icosphere. \pre 0 <= amplitude < 1. \throws InvalidInput
Mesh bumpy_sphere(int subdivisions, double radius = 1.0, double amplitude = 0.1, double frequency = 4.0);

/// Open cylinder of radius `radius` around z, 0 <= z <= `height` (two border loops).
/// \throws InvalidInput
Mesh open_cylinder(int around, int along, double radius = 1.0, double height = 2.0);

/// Cone, open at its base circle (radius `radius`, z = 0), apex (0, 0, height) a single vertex.
/// \throws InvalidInput
Mesh cone(int around, int along, double radius = 1.0, double height = 1.5);

/// Torus around z: `major` segments around the axis (>= 3), `minor` around the tube (>= 3).
/// \pre 0 < minor_radius < major_radius. \throws InvalidInput
Mesh torus(int major, int minor, double major_radius = 1.0, double minor_radius = 0.35);

/// Closed genus-2 surface: the tori of major radius R centred at (-R, 0, 0) and (R, 0, 0), each
/// cut by the plane x = 0 (keeping x <= 0 of the first and x >= 0 of the second, mirror images)
/// and glued along the cut curve, which is a crease. Euler characteristic -2. Each half is meshed
/// along about `resolution` rays (at least 12) of its parameter rectangle, from the
/// cut to the rectangle's border, with resolution/8 rings (at least 2) that follow the cut.
/// \pre 0 < minor_radius < major_radius. \throws InvalidInput
Mesh double_torus(int resolution, double major_radius = 1.0, double minor_radius = 0.35);

/// Möbius strip p(u, v) = ((R + v cos(u/2)) cos u, (R + v cos(u/2)) sin u, v sin(u/2)),
/// u in [0, 2π], |v| <= width/2.
///
/// A Möbius strip is not orientable, and a half-edge mesh (OpenMesh) cannot hold it closed: with
/// the seam welded, OpenMesh refuses the faces of the last strip. This returns the strip *cut open
/// along the seam u = 0*: the vertices of u = 0 and u = 2π are duplicated (same positions, the
/// v order reversed), so the mesh is a consistently oriented disk (Euler characteristic 1, one
/// border loop of 2·around + 2·across edges) that is geometrically the whole Möbius strip.
/// Point samples (`sample("mobius", ...)`) cover the true strip. \throws InvalidInput
Mesh mobius_strip(int around, int across, double radius = 1.0, double width = 0.5);

/// Half-twisted ribbon p(u, v) = (u, v cos(πu/L), v sin(πu/L)), 0 <= u <= L, |v| <= width/2:
/// its two ends are rotated by π against each other. Open, one border loop. \throws InvalidInput
Mesh half_twisted_ribbon(int along, int across, double length = 2.0, double width = 0.5);

/// Closed barrel vault shell along y, 0 <= y <= length: extrados (radius radius + thickness)
/// and intrados (radius `radius`) over θ in [0, π] (x = r cos θ, z = r sin θ), the two feet
/// strips in z = 0 and the two end arches (half annuli) in y = 0 and y = length.
/// `arch` segments over the arch (>= 3); along and across the thickness the counts follow the
/// arch's edge length. \pre 0 < thickness < radius. \throws InvalidInput
Mesh vault_shell(int arch, double radius = 1.0, double thickness = 0.1, double length = 2.0);

/// Open vault sheet: the half cylinder x = R cos θ, z = R sin θ, θ in [0, π], 0 <= y <= length,
/// normals away from the axis (up). \throws InvalidInput
Mesh vault_sheet(int arch, double radius = 1.0, double length = 2.0);

/// Open pointed (gothic, equilateral) arch sheet along y: span from x = -R to x = R, two arcs of
/// radius 2R centred at the opposite springing points, meeting at the crown (0, ·, √3 R) in a
/// crease. `arch` segments over the whole arch (rounded up to even). \throws InvalidInput
Mesh pointed_vault(int arch, double radius = 1.0, double length = 2.0);

/// Open groin vault sheet over the square [-R, R]²: the crossing of the barrel vaults along x
/// (z = sqrt(R² - y²)) and along y (z = sqrt(R² - x²)), each shown where it is the higher one
/// (z = max of both), so four arches open on the four sides and the groins run along the
/// diagonals as creases. Normals up. `arch` segments over each arch (rounded up to even).
/// \throws InvalidInput
Mesh groin_vault(int arch, double radius = 1.0);

/// Closed thin box [-half_size, half_size]² x [-thickness/2, thickness/2].
/// \pre 0 < thickness < 2 half_size. \throws InvalidInput
Mesh thin_plate(int cells, double half_size = 1.0, double thickness = 0.05);

/// Closed U-shaped hairpin: a wall of thickness `thickness` and width `width` (along y) whose
/// centre line runs from (arm_length, 0, c) to (0, 0, c), around a half circle of radius c about
/// the y axis to (0, 0, -c), and back to (arm_length, 0, -c), with c = (gap + thickness) / 2, so
/// the two arms face each other across a gap of width `gap`; flat end caps at x = arm_length.
/// `resolution` segments along each arm (>= 1); around the bend (at least 4), across the width and
/// the thickness the counts follow the arm's edge length. \pre all sizes > 0. \throws InvalidInput
Mesh hairpin(int resolution, double arm_length = 1.5, double width = 0.5, double thickness = 0.1,
             double gap = 0.05);

/// Smooth heightfield z = h(x, y) over [-half_size, half_size]² (a sum of six seeded sine waves,
/// peak amplitude at most `amplitude`, `frequency` the largest wave number in waves per
/// half_size), `cells` x `cells` grid, normals up. \throws InvalidInput
Mesh landscape(int cells, double half_size = 1.0, double amplitude = 0.1, double frequency = 4.0,
               std::uint64_t terrain_seed = 1);

/// The neck mesh and its minimum pathway.
struct NeckMesh {
  Mesh mesh;                               ///< closed genus-0 manifold, outward
  std::array<VertexHandle, 3> pathway = {VertexHandle(), VertexHandle(), VertexHandle()};  ///< the three vertices of the neck's 3-edge cycle
};

/// Two round blobs (unit spheres' caps centred at z = ±1.1) joined through a neck whose narrowest
/// cross-section is a triangle of three vertices with no face filling it: a *minimum pathway*
/// (edge-front paper, Fig. 5). Rings of `around` vertices on the blobs halve toward the neck
/// (around, around/2, ..., 3). \pre around = 3·2^k, k >= 1, around <= 3072. \throws InvalidInput
NeckMesh neck(int around = 12);

/// A closed body with three pinched vertices, split into twins (edgefront/vertex_twins.h), and
/// what the tests need to know about it.
struct PinchedBody {
  /// The body: a horn torus (major radius = tube radius = 1, around z) whose inner equator has
  /// closed to one point, the origin, where its upper and lower sides meet (a pinch inside the
  /// body), and two closed cones (lateral surface and flat base; slant 1.077, base radius 0.4,
  /// axes along +x and -x) whose apexes touch the torus's outer equator at (2, 0, 0) and
  /// (-2, 0, 0) (two parts touching the body at one point). Outward normals. Split as the mesh
  /// loader splits a file: `input_vertices` vertices of which each pinched vertex is one, then one
  /// copy per pinch (3 vertices), linked as twins. Mirror-symmetric in z (vertex positions
  /// exactly, the triangulation too).
  Mesh mesh;
  size_t input_vertices = 0;  ///< vertices before the split (the copies are appended after them)
  /// The groups of twins: {torus vertex at (2, 0, 0), apex of the +x cone}, {torus vertex at
  /// (-2, 0, 0), apex of the -x cone}, {the origin on the upper side, on the lower side}; in each
  /// the original first, the copy second.
  std::array<std::array<VertexHandle, 2>, 3> pinches;
  /// Per cone, its lateral vertices (apex excluded): each lies on a straight edge path from the
  /// apex (a generator), so its geodesic distance from the apex is its Euclidean distance.
  std::array<std::vector<VertexHandle>, 2> cone_sides;
};

/// The pinched body above at a resolution: `around` (even, 6..1024) segments around the torus
/// and around its tube, and around each cone (with around/4 rings, at least 2). Not one of the
/// named shapes of `make` (it is a test mesh with twins). \throws InvalidInput
PinchedBody pinched_body(int around = 12);

/// True when v0, v1, v2 are pairwise joined by edges and no face of `mesh` has exactly these
/// three vertices: a 3-edge cycle that is not a face (a minimum pathway).
/// \throws InvalidInput if a handle is not a live vertex of `mesh` or two are equal.
bool is_minimum_pathway(const Mesh& mesh, VertexHandle v0, VertexHandle v1, VertexHandle v2);

/// All minimum pathways of `mesh`, each as vertex handles in increasing index order, the list
/// sorted. O(E · valence²).
std::vector<std::array<VertexHandle, 3>> find_minimum_pathways(const Mesh& mesh);

/// Appends a small separate component to `mesh`: a flat strip of 10 triangles, two rows of six
/// vertices at x = corner.x + i·spacing (rows y = corner.y + spacing and y = corner.y, z = corner.z).
/// Returns its 12 vertices in the order they were added (upper row i, lower row i, for i = 0..5).
/// Used to test and measure "no path" answers beside a large mesh.
/// \throws InvalidInput for a non-finite corner or a spacing that is not finite and > 0.
std::vector<VertexHandle> add_island(Mesh& mesh, const Vec3& corner = Vec3(0, 0, 1), double spacing = 0.02);

/// Shape parameters shared by `make` and `sample`. Each shape reads only the fields its row in
/// the table above names; the others are ignored (and not validated).
struct ShapeParams {
  /// R: sphere, hemisphere, cylinder, cone base, torus major, vault intrados and half span, Möbius
  /// centre circle; half side of grid, plate, landscape. > 0.
  double radius = 1.0;
  double minor_radius = 0.35; ///< torus and double torus tube radius, 0 < minor_radius < radius
  double inner_radius = 0.5;  ///< nested spheres: inner sphere radius, 0 < inner_radius < radius
  double length = 2.0;        ///< cylinder and cone height, vault length (along y), ribbon length, hairpin arm length; > 0
  double width = 0.5;         ///< ribbon, Möbius strip and hairpin width; > 0 (Möbius strip: width/2 < radius)
  double thickness = 0.1;     ///< vault shell, thin plate and hairpin wall thickness (absolute), 0 < thickness < radius
  double gap = 0.05;          ///< hairpin: distance between the arms' facing sides, > 0
  double amplitude = 0.1;     ///< bumpy sphere: relative bump height in [0, 1); landscape: peak height (absolute)
  double frequency = 4.0;     ///< bumpy sphere: f in sin(f·ux)...; landscape: largest wave number per radius; > 0
  std::uint64_t surface_seed = 1;                   ///< landscape relief and grid jitter (not the sampling seed); any value
  GridVariant grid_variant = GridVariant::regular;  ///< "grid": vertex placement (mesh only)
  GridOutline grid_outline = GridOutline::square;   ///< "grid": outline (mesh and samples)
  double jitter = 0.15;       ///< jittered grid: max displacement per axis in cells, in [0, 1/6)
  double anisotropy = 20.0;   ///< anisotropic grid: cell aspect ratio, in [1, 1000]
};

/// Options of `make`.
struct MeshOptions {
  /// Mesh resolution in [3, 4096]: the number of edges around the shape's main circle or along
  /// its main side (spheres: segments around the equator; icosphere-based shapes use the smallest
  /// subdivision level s with 5·2^s >= resolution; vaults: segments over the arch; grids: cells
  /// along y; hairpin: segments along an arm; neck: ring size, rounded up to 3·2^k). Other
  /// directions follow so that cells stay
  /// roughly square.
  int resolution = 32;
  ShapeParams shape;  ///< shape parameters
};

/// How noise displaces sample points.
enum class NoiseKind {
  along_normal,  ///< p += N(0, σ²) · n  (the default: the surface stays "thick" by σ)
  isotropic      ///< p += N(0, σ² I₃)
};

/// Options of `sample` and `sample_mesh`.
struct SampleOptions {
  std::size_t points = 10000;                   ///< number of points in the output, outliers included, in [1, 10^8]
  std::uint64_t seed = 1;                       ///< sampling seed (same seed, same points); any value
  double noise_sigma = 0.0;                     ///< standard deviation of the Gaussian noise, absolute length units, >= 0
  NoiseKind noise = NoiseKind::along_normal;    ///< direction of the noise; normals are never perturbed
  double outlier_fraction = 0.0;                ///< share of points replaced by outliers, in [0, 1]
  ShapeParams shape;                            ///< shape parameters (ignored by `sample_mesh`)
};

/// Names of all shapes, in the order of the table above.
std::vector<std::string> shape_names();

/// One-line description of a shape. \throws InvalidInput for an unknown name.
std::string describe(const std::string& shape);

/// Mesh of a shape by name (see the table above). \throws InvalidInput for an unknown name or
/// invalid options.
Mesh make(const std::string& shape, const MeshOptions& options = {});

/// Area-uniform oriented samples of a shape by name, with exact analytic unit normals.
/// Noise is added first. Then `round(outlier_fraction · points)` of the points, at random
/// positions in the output, are replaced by outliers: uniform in the bounding box of all the
/// (noisy) samples grown by 10% of its diagonal on each side, with uniformly random unit normals. The "neck" shape has no analytic form: it is sampled from
/// `neck(12)` with face normals. \throws InvalidInput for an unknown name or invalid options.
PointCloud sample(const std::string& shape, const SampleOptions& options = {});

/// Area-uniform samples of a triangle mesh with its face normals (noise and outliers as in
/// `sample`; `options.shape` is ignored). \throws InvalidInput if the mesh has no face of positive
/// area or the options are invalid.
PointCloud sample_mesh(const Mesh& mesh, const SampleOptions& options = {});

}  // namespace edgefront::shapes
