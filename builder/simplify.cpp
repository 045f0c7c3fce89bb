// simplify.cpp: one group's triangles to about half by half-edge collapse in quadric-error order
// (Garland & Heckbert 1997), with the group border locked. Vertices only ever collapse onto existing
// vertices, so every level of the DAG indexes the leaf vertex array.
//
// Written here rather than taken from meshoptimizer 0.18 because the cut must stay a manifold surface
// for every camera, and that needs three tests meshopt does not make:
// - the link condition (Dey et al. 1999): the collapse of u->v is made only if the common neighbours of
//   u and v are exactly the apexes of the triangles on edge uv; otherwise the surface folds into an edge
//   of four triangles;
// - no triangle may flip or become degenerate;
// - a chord, a new edge between two locked border vertices, is made only if `chordAllowed` says so:
//   the DAG builder forbids chords that another cluster already has or that a neighbouring group of the
//   same round could also make, since the cut would then hold that edge four times.
// Locked border vertices never move, so the edges a group shares with its neighbours stay identical.
// The error of a collapse is the root mean square distance, weighted by area, of the target position to
// the planes of the triangles merged into the vertex; the group's error is the largest such distance.
#include <algorithm>
#include <cmath>
#include <queue>
#include <functional>

#include "builder.h"

namespace vgeo {
namespace {

constexpr float kHalvedRatio = 0.55f;
constexpr double kBoundedError = 0.02;  // of the group's bounding box diagonal: beyond it, "relaxed"

struct Quadric {
  double a[10] = {};  // xx xy xz xw yy yz yw zz zw ww
  double weight = 0.0;
  void addPlane(glm::dvec3 n, double d, double w) {
    const double p[4] = {n.x, n.y, n.z, d};
    int k = 0;
    for (int i = 0; i < 4; i++)
      for (int j = i; j < 4; j++) a[k++] += w * p[i] * p[j];
    weight += w;
  }
  void add(const Quadric& q) {
    for (int i = 0; i < 10; i++) a[i] += q.a[i];
    weight += q.weight;
  }
  // Mean squared distance of p to the accumulated planes.
  double meanSquaredDistance(glm::dvec3 p) const {
    double x = p.x, y = p.y, z = p.z;
    double e = a[0] * x * x + 2 * a[1] * x * y + 2 * a[2] * x * z + 2 * a[3] * x + a[4] * y * y + 2 * a[5] * y * z + 2 * a[6] * y +
               a[7] * z * z + 2 * a[8] * z + a[9];
    return weight > 0.0 ? std::max(0.0, e) / weight : 0.0;
  }
};

struct Candidate {
  double cost;
  uint32_t from, to, version;
  bool operator<(const Candidate& o) const {  // std::priority_queue is a max-heap: invert
    if (cost != o.cost) return cost > o.cost;
    if (from != o.from) return from > o.from;
    return to > o.to;
  }
};

class Simplifier {
 public:
  Simplifier(std::vector<uint32_t> triangles, std::vector<glm::dvec3> points, std::vector<uint8_t> locked,
             std::function<bool(uint32_t, uint32_t)> chordAllowed)
      : tri_(std::move(triangles)), p_(std::move(points)), locked_(std::move(locked)), chordAllowed_(std::move(chordAllowed)) {
    const size_t n = p_.size(), m = tri_.size() / 3;
    alive_.assign(m, 1);
    removed_.assign(n, 0);
    aliveCount_ = m;
    vertexTris_.resize(n);
    quadric_.resize(n);
    version_.assign(n, 0);
    rejected_.resize(n);
    for (uint32_t t = 0; t < m; t++) {
      glm::dvec3 a = p_[tri_[3 * t]], b = p_[tri_[3 * t + 1]], c = p_[tri_[3 * t + 2]];
      glm::dvec3 cross = glm::cross(b - a, c - a);
      double len = glm::length(cross);
      glm::dvec3 normal = len > 0.0 ? cross / len : glm::dvec3(0.0);
      double area = 0.5 * len;
      for (int k = 0; k < 3; k++) {
        vertexTris_[tri_[3 * t + k]].push_back(t);
        quadric_[tri_[3 * t + k]].addPlane(normal, -glm::dot(normal, a), area + 1e-30);
      }
    }
    for (uint32_t u = 0; u < n; u++) pushBest(u);
  }

  // Collapses until `targetTriangles` are left or nothing valid remains; returns the largest error.
  double run(size_t targetTriangles) {
    while (aliveCount_ > targetTriangles && !heap_.empty()) {
      Candidate c = heap_.top();
      heap_.pop();
      if (c.version != version_[c.from] || dead(c.from) || dead(c.to)) continue;
      if (!valid(c.from, c.to)) {
        rejected_[c.from].push_back(c.to);
        pushBest(c.from);
        continue;
      }
      maxCost_ = std::max(maxCost_, c.cost);
      collapse(c.from, c.to);
    }
    return std::sqrt(maxCost_);
  }

  size_t triangleCount() const { return aliveCount_; }
  std::vector<uint32_t> triangles() const {
    std::vector<uint32_t> out;
    out.reserve(aliveCount_ * 3);
    for (size_t t = 0; t < alive_.size(); t++)
      if (alive_[t]) out.insert(out.end(), {tri_[3 * t], tri_[3 * t + 1], tri_[3 * t + 2]});
    return out;
  }

 private:
  bool dead(uint32_t v) const { return removed_[v]; }

  // Neighbours of u (sorted, unique) from its live triangles.
  void neighbours(uint32_t u, std::vector<uint32_t>& out) const {
    out.clear();
    for (uint32_t t : vertexTris_[u])
      if (alive_[t])
        for (int k = 0; k < 3; k++)
          if (tri_[3 * t + k] != u) out.push_back(tri_[3 * t + k]);
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
  }

  void pushBest(uint32_t u) {
    if (locked_[u]) return;
    neighbours(u, scratchA_);
    double best = INFINITY;
    uint32_t target = UINT32_MAX;
    for (uint32_t v : scratchA_) {
      if (std::find(rejected_[u].begin(), rejected_[u].end(), v) != rejected_[u].end()) continue;
      Quadric q = quadric_[u];
      q.add(quadric_[v]);
      double cost = q.meanSquaredDistance(p_[v]);
      if (cost < best) best = cost, target = v;
    }
    if (target != UINT32_MAX) heap_.push({best, u, target, version_[u]});
  }

  bool valid(uint32_t u, uint32_t v) {
    // Link condition: common neighbours == apexes of the triangles on edge uv.
    neighbours(u, scratchA_);
    neighbours(v, scratchB_);
    scratchC_.clear();
    std::set_intersection(scratchA_.begin(), scratchA_.end(), scratchB_.begin(), scratchB_.end(), std::back_inserter(scratchC_));
    size_t apexes = 0;
    for (uint32_t t : vertexTris_[u]) {
      if (!alive_[t]) continue;
      const uint32_t* x = &tri_[3 * t];
      if (x[0] != v && x[1] != v && x[2] != v) continue;
      apexes++;
      uint32_t apex = x[0] != u && x[0] != v ? x[0] : x[1] != u && x[1] != v ? x[1] : x[2];
      if (!std::binary_search(scratchC_.begin(), scratchC_.end(), apex)) { stat[0]++; return false; }
    }
    if (apexes == 0 || scratchC_.size() != apexes) { stat[0]++; return false; }
    // No flipped or degenerate triangle.
    for (uint32_t t : vertexTris_[u]) {
      if (!alive_[t]) continue;
      const uint32_t* x = &tri_[3 * t];
      if (x[0] == v || x[1] == v || x[2] == v) continue;
      glm::dvec3 before[3], after[3];
      for (int k = 0; k < 3; k++) {
        before[k] = p_[x[k]];
        after[k] = x[k] == u ? p_[v] : p_[x[k]];
      }
      glm::dvec3 n0 = glm::cross(before[1] - before[0], before[2] - before[0]);
      glm::dvec3 n1 = glm::cross(after[1] - after[0], after[2] - after[0]);
      double l0 = glm::length(n0), l1 = glm::length(n1);
      if (l1 <= 1e-12 * (glm::dot(after[1] - after[0], after[1] - after[0]) + glm::dot(after[2] - after[0], after[2] - after[0])))
        { stat[1]++; return false; }
      if (l0 > 0.0 && glm::dot(n0, n1) < 0.2 * l0 * l1) { stat[2]++; return false; }
    }
    // Chords: new edges v-w between two locked vertices.
    if (locked_[v])
      for (uint32_t w : scratchA_)
        if (w != v && locked_[w] && !std::binary_search(scratchB_.begin(), scratchB_.end(), w) && !chordAllowed_(v, w)) { stat[3]++; return false; }
    return true;
  }

  void collapse(uint32_t u, uint32_t v) {
    neighbours(u, scratchA_);
    for (uint32_t t : vertexTris_[u]) {
      if (!alive_[t]) continue;
      uint32_t* x = &tri_[3 * t];
      if (x[0] == v || x[1] == v || x[2] == v) {
        alive_[t] = 0;
        aliveCount_--;
        continue;
      }
      for (int k = 0; k < 3; k++)
        if (x[k] == u) x[k] = v;
      vertexTris_[v].push_back(t);
    }
    vertexTris_[u].clear();
    removed_[u] = 1;
    quadric_[v].add(quadric_[u]);
    // Costs change for v and every vertex around it.
    std::vector<uint32_t> touched = scratchA_;
    touched.push_back(v);
    for (uint32_t w : touched) {
      if (w == u) continue;
      version_[w]++;
      rejected_[w].clear();
      pushBest(w);
    }
  }

  std::vector<uint32_t> tri_;
  std::vector<glm::dvec3> p_;
  std::vector<uint8_t> locked_;
  std::function<bool(uint32_t, uint32_t)> chordAllowed_;
  std::vector<uint8_t> alive_, removed_;
  size_t aliveCount_ = 0;
  std::vector<std::vector<uint32_t>> vertexTris_;
  std::vector<Quadric> quadric_;
  std::vector<uint32_t> version_;
  std::vector<std::vector<uint32_t>> rejected_;
  std::priority_queue<Candidate> heap_;
  std::vector<uint32_t> scratchA_, scratchB_, scratchC_;
  double maxCost_ = 0.0;
 public:
  size_t stat[4] = {0,0,0,0};
};

}  // namespace

SimplifiedGroup simplifyGroup(const std::vector<uint32_t>& indices, const std::vector<glm::vec3>& positions,
                              const std::function<bool(uint32_t, uint32_t)>& chordAllowed) {
  // Local vertex ids in order of first use.
  thread_local std::vector<uint32_t> localOf;
  if (localOf.size() < positions.size()) localOf.assign(positions.size(), UINT32_MAX);
  std::vector<uint32_t> globals, local(indices.size());
  for (size_t i = 0; i < indices.size(); i++) {
    uint32_t& slot = localOf[indices[i]];
    if (slot == UINT32_MAX) {
      slot = uint32_t(globals.size());
      globals.push_back(indices[i]);
    }
    local[i] = slot;
  }
  for (uint32_t g : globals) localOf[g] = UINT32_MAX;

  // Locked: vertices on a directed edge whose reverse is absent (the group border).
  std::vector<uint64_t> edges;
  edges.reserve(local.size());
  for (size_t t = 0; t + 2 < local.size(); t += 3)
    for (int k = 0; k < 3; k++) edges.push_back(uint64_t(local[t + size_t(k)]) << 32 | local[t + size_t((k + 1) % 3)]);
  std::sort(edges.begin(), edges.end());
  std::vector<uint8_t> locked(globals.size(), 0);
  for (uint64_t e : edges)
    if (!std::binary_search(edges.begin(), edges.end(), (e << 32) | (e >> 32))) locked[e >> 32] = locked[e & 0xffffffffu] = 1;

  std::vector<glm::dvec3> points(globals.size());
  glm::dvec3 lower(INFINITY), upper(-INFINITY);
  for (size_t i = 0; i < globals.size(); i++) {
    points[i] = glm::dvec3(positions[globals[i]]);
    lower = glm::min(lower, points[i]);
    upper = glm::max(upper, points[i]);
  }
  const size_t triangles = indices.size() / 3;
  std::vector<uint8_t> lockedCopy = locked;
  Simplifier s(std::move(local), std::move(points), std::move(locked),
               [&](uint32_t a, uint32_t b) { return chordAllowed(globals[a], globals[b]); });
  double error = s.run(triangles / 2);
  if (getenv("VGEO_DEBUG") && s.triangleCount() > size_t(float(triangles) * kHalvedRatio)) {
    // components of the input triangles by shared edges
    std::vector<uint32_t> comp(triangles); for (size_t i = 0; i < triangles; i++) comp[i] = uint32_t(i);
    std::function<uint32_t(uint32_t)> find = [&](uint32_t x) { while (comp[x] != x) x = comp[x] = comp[comp[x]]; return x; };
    std::vector<std::pair<uint64_t, uint32_t>> es;
    for (size_t t = 0; t < triangles; t++) for (int k = 0; k < 3; k++) { uint32_t a = indices[3*t+k], b = indices[3*t+(k+1)%3]; es.push_back({uint64_t(std::min(a,b))<<32|std::max(a,b), uint32_t(t)}); }
    std::sort(es.begin(), es.end());
    for (size_t i = 0; i + 1 < es.size(); i++) if (es[i].first == es[i+1].first) comp[find(es[i].second)] = find(es[i+1].second);
    size_t nc = 0; for (size_t i = 0; i < triangles; i++) nc += find(uint32_t(i)) == i;
    fprintf(stderr, "components %zu\n", nc);
  }
  if (getenv("VGEO_DEBUG") && s.triangleCount() > size_t(float(triangles) * kHalvedRatio)) fprintf(stderr, "stuck %zu -> %zu link %zu degen %zu flip %zu chord %zu locked %zu of %zu\n", triangles, s.triangleCount(), s.stat[0], s.stat[1], s.stat[2], s.stat[3], size_t(std::count(lockedCopy.begin(), lockedCopy.end(), 1)), lockedCopy.size());
  SimplifiedGroup result;
  result.error = float(error);
  result.halved = s.triangleCount() <= size_t(float(triangles) * kHalvedRatio);
  result.relaxation = error > kBoundedError * glm::distance(lower, upper) ? 1 : 0;
  result.indices = s.triangles();
  for (uint32_t& v : result.indices) v = globals[v];
  return result;
}

}  // namespace vgeo
