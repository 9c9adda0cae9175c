// tetquality_precise: the reference judge's tet measures at full precision.
//
// Reads a TetGen .node/.ele pair (pass the prefix or the .ele path) and prints the judge's
// summary lines with %.17g, so that other implementations can be compared to ~1e-15 rather
// than to the judge's 4 printed decimals. The measures are the shared judge's own
// tq::measure() and tq::Summary, #included from the shared tools directory (not a copy).
//
// Input: '#' comments anywhere; node and element indices may start at 0 or 1 (nodes are
// looked up by the index they carry); node attributes, boundary markers, element attributes
// and the extra nodes of 10-node tets are skipped.
//
// Build: g++ -O2 -std=c++17 -o tetquality_precise tools/tetquality_precise.cpp
//        (add -DTQ_HEADER='"/abs/path/tet_quality.h"' when ../shared is elsewhere)
// Usage: tetquality_precise PREFIX[.ele]
#include <array>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <unordered_map>
#include <vector>

// The shared judge's header, relative to this file (the checkout sits beside ../shared);
// -DTQ_HEADER='"/path/to/tet_quality.h"' names it elsewhere.
#ifdef TQ_HEADER
#include TQ_HEADER
#else
#include "../../shared/tools/cgal_ref/tet_quality.h"
#endif

namespace {

[[noreturn]] void fail(const std::string& msg) {
  std::fprintf(stderr, "tetquality_precise: %s\n", msg.c_str());
  std::exit(1);
}

// Non-empty lines with '#' comments removed, split into tokens.
std::vector<std::vector<std::string>> records(const std::string& path) {
  std::ifstream in(path);
  if (!in) fail("cannot open " + path);
  std::vector<std::vector<std::string>> out;
  std::string line;
  while (std::getline(in, line)) {
    auto h = line.find('#');
    if (h != std::string::npos) line.resize(h);
    std::istringstream ss(line);
    std::vector<std::string> toks;
    for (std::string t; ss >> t;) toks.push_back(t);
    if (!toks.empty()) out.push_back(std::move(toks));
  }
  return out;
}

double num(const std::string& s, const std::string& where) {
  char* end = nullptr;
  double v = std::strtod(s.c_str(), &end);
  if (end == s.c_str() || *end != '\0') fail("bad number '" + s + "' in " + where);
  return v;
}

long integer(const std::string& s, const std::string& where) {
  double v = num(s, where);
  if (v != static_cast<double>(static_cast<long>(v))) fail("bad index '" + s + "' in " + where);
  return static_cast<long>(v);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s PREFIX[.ele]\n", argv[0]);
    return 2;
  }
  std::string prefix = argv[1];
  if (prefix.size() > 4 && prefix.compare(prefix.size() - 4, 4, ".ele") == 0) prefix.resize(prefix.size() - 4);
  const std::string node_path = prefix + ".node", ele_path = prefix + ".ele";

  auto nodes = records(node_path);
  if (nodes.empty()) fail("empty " + node_path);
  long nv = integer(nodes[0].at(0), node_path);
  if (nodes[0].size() > 1 && integer(nodes[0][1], node_path) != 3) fail("only 3D .node files are supported");
  if (static_cast<long>(nodes.size()) - 1 < nv) fail("too few nodes in " + node_path);
  std::vector<tq::V3> P(nv);
  std::unordered_map<long, long> id;  // file index -> position, so 0- and 1-based both work
  for (long i = 0; i < nv; ++i) {
    const auto& r = nodes[i + 1];
    if (r.size() < 4) fail("short node record in " + node_path);
    id[integer(r[0], node_path)] = i;
    for (int d = 0; d < 3; ++d) P[i][d] = num(r[d + 1], node_path);
  }

  auto eles = records(ele_path);
  if (eles.empty()) fail("empty " + ele_path);
  long nt = integer(eles[0].at(0), ele_path);
  long npt = eles[0].size() > 1 ? integer(eles[0][1], ele_path) : 4;
  if (npt != 4 && npt != 10) fail("expected 4 or 10 nodes per tet");
  if (static_cast<long>(eles.size()) - 1 < nt) fail("too few tets in " + ele_path);
  tq::Summary s;
  for (long t = 0; t < nt; ++t) {
    const auto& r = eles[t + 1];
    if (static_cast<long>(r.size()) < 1 + npt) fail("short tet record in " + ele_path);
    std::array<long, 4> v{};
    for (int d = 0; d < 4; ++d) {
      auto it = id.find(integer(r[d + 1], ele_path));
      if (it == id.end()) fail("tet " + r[0] + " uses an unknown node " + r[d + 1]);
      v[d] = it->second;
    }
    s.add(tq::measure(P[v[0]], P[v[1]], P[v[2]], P[v[3]]));
  }
  std::printf("vertices %ld\n", nv);
  std::printf("tets %ld\n", s.n);
  std::printf("volume %.17g\n", s.volume);
  std::printf("inverted_or_flat %ld\n", s.inverted);
  std::printf("min_dihedral_deg %.17g\n", s.min_dih);
  std::printf("max_dihedral_deg %.17g\n", s.max_dih);
  std::printf("max_radius_edge_ratio %.17g\n", s.max_ratio);
  std::printf("mean_radius_edge_ratio %.17g\n", s.n ? s.sum_ratio / s.n : 0.0);
  std::printf("tets_radius_edge_over_1.414 %ld\n", s.ratio_over_sqrt2);
  std::printf("tets_radius_edge_over_2 %ld\n", s.ratio_over_2);
  std::printf("min_vol_length_quality %.17g\n", s.min_vl);
  std::printf("tets_min_dihedral_below_5 %ld\n", s.below5);
  std::printf("tets_min_dihedral_below_10 %ld\n", s.below10);
  std::printf("tets_min_dihedral_below_20 %ld\n", s.below20);
  return 0;
}
