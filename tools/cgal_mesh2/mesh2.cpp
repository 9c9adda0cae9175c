// Reference 2D Delaunay refinement with CGAL Mesh_2 (refine_Delaunay_mesh_2), for the
// side-by-side table of issue 66 (tools/bench_mesh2d_anchors.py, tests/mesh2d_anchors.rs).
//
// Reads a Triangle 2D .poly (vertices, segments, hole seeds; '#' comments; 0- or 1-based as
// the first vertex says; a vertex count of 0 reads the .node beside it; vertex attributes,
// markers and regional attributes are skipped), inserts the vertices and segments into a
// constrained Delaunay triangulation (Exact_predicates_inexact_constructions_kernel), and
// refines it with the hole seeds as seeds (their components left out).
//
// Usage: cgal_mesh2 FILE.poly [--min-angle DEG] [--size S | --area A]
//   --min-angle DEG  the shape bound B = sin^2(DEG) (default 30: B = 0.25; CGAL's
//                    termination guarantee holds to about 20.7 deg, B = 0.125)
//   --size S         Delaunay_mesh_size_criteria_2(B, S): no edge longer than S (default 0: none)
//   --area A         Area_criteria below: shape bound B and no triangle larger than A, as
//                    Triangle's -a (the like-for-like comparison with Triangle and fepre).
//                    Not CGAL's undocumented Delaunay_mesh_area_criteria_2: in CGAL 5.5 its
//                    sine is half the true one (it squares the area where the size criteria
//                    square twice the area), so B = 0.25 never holds and refinement runs away.
// Output: one JSON object: triangles, vertices, min_angle, max_angle (degrees, over the
// triangles in the domain), cdt_seconds (insertion of points and constraints) and
// refine_seconds (the refine_Delaunay_mesh_2 call alone), both by std::chrono::steady_clock.
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Delaunay_mesher_2.h>
#include <CGAL/Delaunay_mesh_face_base_2.h>
#include <CGAL/Delaunay_mesh_vertex_base_2.h>
#include <CGAL/Delaunay_mesh_size_criteria_2.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
typedef CGAL::Delaunay_mesh_vertex_base_2<K> Vb;
typedef CGAL::Delaunay_mesh_face_base_2<K> Fb;
typedef CGAL::Triangulation_data_structure_2<Vb, Fb> Tds;
typedef CGAL::Constrained_Delaunay_triangulation_2<K, Tds> CDT;
typedef CDT::Point Point;

// Delaunay_mesh_size_criteria_2 with the size replaced by the triangle's area: a triangle is
// imperatively bad when its area exceeds A (quality.size() = area / A > 1), bad when the
// squared sine of its smallest angle is below B.
template <class Tr>
class Area_criteria : public CGAL::Delaunay_mesh_size_criteria_2<Tr> {
  typedef CGAL::Delaunay_mesh_size_criteria_2<Tr> Base;
  double area_bound;

 public:
  typedef typename Base::Quality Quality;
  Area_criteria(double B, double A) : Base(B, 0.0), area_bound(A) {}

  class Is_bad : public Base::Is_bad {
    double A;

   public:
    Is_bad(double B, double A, const typename Tr::Geom_traits& t) : Base::Is_bad(B, 1.0, t), A(A) {}
    CGAL::Mesh_2::Face_badness operator()(const Quality q) const { return Base::Is_bad::operator()(q); }
    CGAL::Mesh_2::Face_badness operator()(const typename Tr::Face_handle& fh, Quality& q) const {
      const auto &pa = fh->vertex(0)->point(), &pb = fh->vertex(1)->point(), &pc = fh->vertex(2)->point();
      double area = 0.5 * std::fabs((pb.x() - pa.x()) * (pc.y() - pa.y()) - (pb.y() - pa.y()) * (pc.x() - pa.x()));
      double a = CGAL::to_double(CGAL::squared_distance(pb, pc)), b = CGAL::to_double(CGAL::squared_distance(pc, pa)),
             c = CGAL::to_double(CGAL::squared_distance(pa, pb));
      // the smallest angle is opposite the shortest side: sin = 2 area / (product of the others)
      double lo = std::min(a, std::min(b, c));
      double prod = (a == lo) ? b * c : (b == lo) ? a * c : a * b;
      q.first = 4.0 * area * area / prod;
      q.second = area / A;
      if (q.second > 1.0) return CGAL::Mesh_2::IMPERATIVELY_BAD;
      if (q.first < this->B) return CGAL::Mesh_2::BAD;
      return CGAL::Mesh_2::NOT_BAD;
    }
  };
  Is_bad is_bad_object() const { return Is_bad(this->bound(), area_bound, this->traits); }
};

static void die(const std::string& msg) {
  std::fprintf(stderr, "cgal_mesh2: %s\n", msg.c_str());
  std::exit(2);
}

// The data lines of a file: comments stripped, blank lines skipped, split into fields.
static std::vector<std::vector<std::string>> data_lines(const std::string& path) {
  std::ifstream in(path);
  if (!in) die("cannot open " + path);
  std::vector<std::vector<std::string>> out;
  std::string line;
  while (std::getline(in, line)) {
    line = line.substr(0, line.find('#'));
    std::istringstream ss(line);
    std::vector<std::string> f;
    std::string w;
    while (ss >> w) f.push_back(w);
    if (!f.empty()) out.push_back(f);
  }
  return out;
}

struct Poly {
  std::vector<Point> points;
  std::vector<std::pair<int, int>> segments;
  std::vector<Point> holes;
};

static double num(const std::vector<std::string>& f, size_t k, const std::string& path) {
  if (k >= f.size()) die(path + ": a line has too few fields");
  return std::strtod(f[k].c_str(), nullptr);
}

// Reads "count dim attrs markers" and the vertices after it from lines[i...]; returns the base.
static long read_vertices(const std::vector<std::vector<std::string>>& L, size_t& i, std::vector<Point>& pts, const std::string& path) {
  if (i >= L.size()) die(path + ": no vertex count");
  long n = std::atol(L[i][0].c_str());
  ++i;
  long base = 0;
  for (long k = 0; k < n; ++k, ++i) {
    if (i >= L.size()) die(path + ": the file ends inside the vertex list");
    if (k == 0) base = std::atol(L[i][0].c_str());
    pts.emplace_back(num(L[i], 1, path), num(L[i], 2, path));
  }
  return base;
}

static Poly read_poly(const std::string& path) {
  Poly p;
  auto L = data_lines(path);
  size_t i = 0;
  long base = read_vertices(L, i, p.points, path);
  if (p.points.empty()) {
    std::string node = path.substr(0, path.rfind('.')) + ".node";
    auto N = data_lines(node);
    size_t j = 0;
    base = read_vertices(N, j, p.points, node);
  }
  if (i >= L.size()) die(path + ": no segment count");
  long m = std::atol(L[i][0].c_str());
  ++i;
  for (long k = 0; k < m; ++k, ++i) {
    if (i >= L.size()) die(path + ": the file ends inside the segment list");
    long a = std::atol(L[i][1].c_str()) - base, b = std::atol(L[i][2].c_str()) - base;
    if (a < 0 || b < 0 || a >= (long)p.points.size() || b >= (long)p.points.size()) die(path + ": a segment names a missing vertex");
    p.segments.emplace_back((int)a, (int)b);
  }
  if (i < L.size()) {
    long h = std::atol(L[i][0].c_str());
    ++i;
    for (long k = 0; k < h; ++k, ++i) {
      if (i >= L.size()) die(path + ": the file ends inside the hole list");
      p.holes.emplace_back(num(L[i], 1, path), num(L[i], 2, path));
    }
  }
  return p;
}

static double angle_at(const Point& a, const Point& b, const Point& c) {
  double ux = b.x() - a.x(), uy = b.y() - a.y(), vx = c.x() - a.x(), vy = c.y() - a.y();
  return std::atan2(std::fabs(ux * vy - uy * vx), ux * vx + uy * vy) * 180.0 / M_PI;
}

int main(int argc, char** argv) {
  if (argc < 2) die("usage: cgal_mesh2 FILE.poly [--min-angle DEG] [--size S | --area A]");
  std::string path = argv[1];
  double min_angle = 30.0, size = 0.0, area = 0.0;
  for (int k = 2; k < argc; ++k) {
    std::string a = argv[k];
    if (k + 1 >= argc) die("missing value after " + a);
    double v = std::strtod(argv[++k], nullptr);
    if (a == "--min-angle") min_angle = v;
    else if (a == "--size") size = v;
    else if (a == "--area") area = v;
    else die("unknown option " + a);
  }
  Poly poly = read_poly(path);
  double s = std::sin(min_angle * M_PI / 180.0);
  double B = s * s;

  auto t0 = std::chrono::steady_clock::now();
  CDT cdt;
  std::vector<CDT::Vertex_handle> vh;
  vh.reserve(poly.points.size());
  for (const Point& q : poly.points) vh.push_back(cdt.insert(q));
  for (auto& e : poly.segments) cdt.insert_constraint(vh[e.first], vh[e.second]);
  auto t1 = std::chrono::steady_clock::now();
  if (area > 0.0) {
    CGAL::refine_Delaunay_mesh_2(cdt, poly.holes.begin(), poly.holes.end(), Area_criteria<CDT>(B, area));
  } else {
    CGAL::refine_Delaunay_mesh_2(cdt, poly.holes.begin(), poly.holes.end(), CGAL::Delaunay_mesh_size_criteria_2<CDT>(B, size));
  }
  auto t2 = std::chrono::steady_clock::now();

  long tris = 0;
  double lo = 180.0, hi = 0.0;
  for (auto f = cdt.finite_faces_begin(); f != cdt.finite_faces_end(); ++f) {
    if (!f->is_in_domain()) continue;
    ++tris;
    const Point &a = f->vertex(0)->point(), &b = f->vertex(1)->point(), &c = f->vertex(2)->point();
    for (double x : {angle_at(a, b, c), angle_at(b, c, a), angle_at(c, a, b)}) {
      lo = std::min(lo, x);
      hi = std::max(hi, x);
    }
  }
  double cdt_s = std::chrono::duration<double>(t1 - t0).count();
  double refine_s = std::chrono::duration<double>(t2 - t1).count();
  std::printf("{\"file\": \"%s\", \"criteria\": \"%s\", \"min_angle_asked\": %.17g, \"shape_bound\": %.17g, \"size_bound\": %.17g, "
              "\"triangles\": %ld, \"vertices\": %zu, \"min_angle\": %.6f, \"max_angle\": %.6f, \"cdt_seconds\": %.6f, \"refine_seconds\": %.6f}\n",
              path.c_str(), area > 0.0 ? "area" : "size", min_angle, B, area > 0.0 ? area : size, tris, (size_t)cdt.number_of_vertices(), lo, hi, cdt_s, refine_s);
  return 0;
}
