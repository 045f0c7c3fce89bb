// simplify.cpp: one group's triangles to about half (the DAG builder sets the count) by half-edge
// collapse in quadric-error order (Garland & Heckbert 1997), with the group border locked. Vertices
// only ever collapse onto existing vertices, so every level of the DAG indexes the leaf vertex array.
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
// The surface's own open boundary (edges no other cluster has) is not locked: a vertex on it alone
// collapses along it onto a boundary neighbour, its quadric holding the planes through each boundary
// edge perpendicular to its triangle (Garland & Heckbert's boundary constraint), so an open mesh keeps
// its outline while it is reduced instead of carrying every boundary vertex to the root.
// Collapses are ordered by the root mean square distance, weighted by area, of the target position to
// the planes of the triangles merged into the vertex. The group's error is the larger of the largest
// such distance and the one-sided Hausdorff distance of the removed vertices to the result.
#include <algorithm>
#include <cmath>

#include "builder.h"

namespace vgeo {

namespace {

constexpr float kHalvedRatio = 0.55f;
constexpr double kBoundedError = 0.02;   // of the group's bounding box diagonal: beyond it, "relaxed"
constexpr double kBoundaryWeight = 4.0;  // boundary planes against the surface's: keeps outlines in place

enum VertexKind : uint8_t { kFree = 0, kLocked = 1, kOpen = 2 };  // kOpen: on the open boundary only

struct Quadric {
  double a[10] = {};  // xx xy xz xw yy yz yw zz zw ww
  double weight = 0.0;
  static Quadric plane(glm::dvec3 n, double d, double w) {
    const double p[4] = {n.x, n.y, n.z, d};
    Quadric q;
    int k = 0;
    for (int i = 0; i < 4; i++)
      for (int j = i; j < 4; j++) q.a[k++] = w * p[i] * p[j];
    q.weight = w;
    return q;
  }
  void add(const Quadric& q) {
    for (int i = 0; i < 10; i++) a[i] += q.a[i];
    weight += q.weight;
  }
  double evaluate(glm::dvec3 p) const {
    double x = p.x, y = p.y, z = p.z;
    return a[0] * x * x + 2 * a[1] * x * y + 2 * a[2] * x * z + 2 * a[3] * x + a[4] * y * y + 2 * a[5] * y * z +
           2 * a[6] * y + a[7] * z * z + 2 * a[8] * z + a[9];
  }
  // Mean squared distance of p to the planes of this quadric and `other` together, given
  // other.evaluate(p) (a vertex's own quadric at its own position is kept, not recomputed).
  double meanSquaredDistance(glm::dvec3 p, const Quadric& other, double otherAtP) const {
    double w = weight + other.weight;
    return w > 0.0 ? std::max(0.0, evaluate(p) + otherAtP) / w : 0.0;
  }
};

struct Candidate {
  double cost;
  uint32_t from, to;
};

// The vertices with a candidate, cheapest first (then by vertex id), one entry each: a vertex's entry
// is moved in place when its candidate changes, so no stale entries pile up and are popped. An entry
// holds its cost, so the sifts compare without a load from elsewhere.
class CandidateHeap {
 public:
  explicit CandidateHeap(size_t vertices) : at_(vertices, kAbsent) {}
  bool empty() const { return heap_.empty(); }
  uint32_t top() const { return heap_[0].vertex; }
  double topCost() const { return heap_[0].cost; }
  // Enters or moves v with this cost.
  void set(uint32_t v, double cost) {
    if (at_[v] == kAbsent) {
      at_[v] = uint32_t(heap_.size());
      heap_.push_back({cost, v});
    }
    heap_[at_[v]].cost = cost;
    siftDown(siftUp(at_[v]));
  }
  void remove(uint32_t v) {
    const uint32_t i = at_[v];
    if (i == kAbsent) return;
    at_[v] = kAbsent;
    const Entry last = heap_.back();
    heap_.pop_back();
    if (i == heap_.size()) return;
    place(i, last);
    siftDown(siftUp(i));
  }

 private:
  struct Entry {
    double cost;
    uint32_t vertex;
  };
  static constexpr uint32_t kAbsent = UINT32_MAX;
  static bool before(const Entry& a, const Entry& b) {
    return a.cost != b.cost ? a.cost < b.cost : a.vertex < b.vertex;
  }
  void place(uint32_t i, const Entry& e) {
    heap_[i] = e;
    at_[e.vertex] = i;
  }
  uint32_t siftUp(uint32_t i) {
    const Entry e = heap_[i];
    while (i > 0 && before(e, heap_[(i - 1) / 2])) {
      place(i, heap_[(i - 1) / 2]);
      i = (i - 1) / 2;
    }
    place(i, e);
    return i;
  }
  void siftDown(uint32_t i) {
    const Entry e = heap_[i];
    const uint32_t n = uint32_t(heap_.size());
    for (;;) {
      uint32_t child = 2 * i + 1;
      if (child >= n) break;
      if (child + 1 < n && before(heap_[child + 1], heap_[child])) child++;
      if (!before(heap_[child], e)) break;
      place(i, heap_[child]);
      i = child;
    }
    place(i, e);
  }
  std::vector<Entry> heap_;
  std::vector<uint32_t> at_;
};

class Simplifier {
 public:
  // kind[v]: VertexKind; openEdges: local (min << 32 | max), ascending.
  Simplifier(std::vector<uint32_t> triangles, std::vector<glm::dvec3> points, std::vector<uint8_t> kind,
             const std::vector<uint64_t>& openEdges, std::function<bool(uint32_t, uint32_t)> chordAllowed)
      : tri_(std::move(triangles)),
        p_(std::move(points)),
        kind_(std::move(kind)),
        chordAllowed_(std::move(chordAllowed)),
        heap_(p_.size()) {
    const size_t n = p_.size(), m = tri_.size() / 3;
    alive_.assign(m, 1);
    removed_.assign(n, 0);
    collapsedInto_.assign(n, UINT32_MAX);
    aliveCount_ = m;
    // Triangle lists of the vertices in one pool: list v is pool_[start_[v] .. start_[v] + size_[v]),
    // with room up to capacity_[v]; a list that outgrows its room moves to the pool's end.
    start_.assign(n, 0);
    size_.assign(n, 0);
    capacity_.assign(n, 0);
    for (uint32_t c : tri_) capacity_[c]++;
    uint32_t total = 0;
    for (uint32_t v = 0; v < n; v++) {
      start_[v] = total;
      capacity_[v] += 2;
      total += capacity_[v];
    }
    pool_.resize(total);
    quadric_.resize(n);
    bestTarget_.assign(n, UINT32_MAX);
    rejected_.resize(n);
    for (uint32_t t = 0; t < m; t++) {
      glm::dvec3 a = p_[tri_[3 * t]], b = p_[tri_[3 * t + 1]], c = p_[tri_[3 * t + 2]];
      glm::dvec3 cross = glm::cross(b - a, c - a);
      double len = glm::length(cross);
      glm::dvec3 normal = len > 0.0 ? cross / len : glm::dvec3(0.0);
      double area = 0.5 * len;
      const Quadric face = Quadric::plane(normal, -glm::dot(normal, a), area + 1e-30);
      for (int k = 0; k < 3; k++) {
        append(tri_[3 * t + k], t);
        quadric_[tri_[3 * t + k]].add(face);
      }
      if (openEdges.empty()) continue;
      for (int k = 0; k < 3; k++) {
        uint32_t e0 = tri_[3 * t + k], e1 = tri_[3 * t + (k + 1) % 3];
        if (!std::binary_search(openEdges.begin(), openEdges.end(), undirectedEdge(e0, e1))) continue;
        glm::dvec3 edge = p_[e1] - p_[e0];
        glm::dvec3 side = glm::cross(edge, normal);
        double length = glm::length(side);
        if (!(length > 0.0)) continue;
        side /= length;
        double weight = kBoundaryWeight * glm::dot(edge, edge);
        const Quadric boundary = Quadric::plane(side, -glm::dot(side, p_[e0]), weight);
        quadric_[e0].add(boundary);
        quadric_[e1].add(boundary);
      }
    }
    selfCost_.resize(n);
    for (uint32_t v = 0; v < n; v++) selfCost_[v] = quadric_[v].evaluate(p_[v]);
    seen_.assign(n, 0);
    for (uint32_t u = 0; u < n; u++) pushBest(u);
  }

  // Collapses until `targetTriangles` are left or nothing valid remains; returns the largest error.
  double run(size_t targetTriangles) {
    while (aliveCount_ > targetTriangles && !heap_.empty()) {
      const uint32_t u = heap_.top();
      const Candidate c{heap_.topCost(), u, bestTarget_[u]};
      heap_.remove(u);
      if (dead(c.to)) continue;
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

  // One-sided Hausdorff error: for every removed vertex, the distance from its position to the nearest
  // final triangle around the vertex it ended up in (an upper bound of its distance to the simplified
  // surface). The quadric's mean distance alone let coarse levels deviate by more than their error.
  // Distances are compared squared, with one square root of the result: the root of the largest is the
  // largest root, to the bit.
  double removedVertexError() {
    double worst = 0.0;
    for (uint32_t u = 0; u < p_.size(); u++) {
      if (!removed_[u]) continue;
      uint32_t w = u;
      while (removed_[w]) w = collapsedInto_[w];
      // Once a triangle is within `worst`, this vertex cannot raise it: the rest are not measured.
      double best = INFINITY;
      for (uint32_t i = 0; i < size_[w] && best > worst; i++) {
        uint32_t t = trianglesOf(w)[i];
        if (alive_[t])
          best = std::min(
              best, pointTriangleDistanceSquared(p_[u], p_[tri_[3 * t]], p_[tri_[3 * t + 1]], p_[tri_[3 * t + 2]]));
      }
      if (std::isfinite(best)) worst = std::max(worst, best);
    }
    return std::sqrt(worst);
  }
  std::vector<uint32_t> triangles() const {
    std::vector<uint32_t> out;
    out.reserve(aliveCount_ * 3);
    for (size_t t = 0; t < alive_.size(); t++)
      if (alive_[t]) out.insert(out.end(), {tri_[3 * t], tri_[3 * t + 1], tri_[3 * t + 2]});
    return out;
  }

 private:
  bool dead(uint32_t v) const { return removed_[v]; }

  // A stamp no vertex holds in seen_ yet.
  uint32_t nextStamp() {
    if (++stamp_ == 0) std::fill(seen_.begin(), seen_.end(), 0), stamp_ = 1;
    return stamp_;
  }

  // Neighbours of u (unique, in the order met) from its live triangles, each stamped in seen_ with
  // the stamp returned; drops dead triangles from u's list.
  uint32_t neighbours(uint32_t u, std::vector<uint32_t>& out) {
    const uint32_t stamp = nextStamp();
    out.resize(2 * size_t(size_[u]));
    uint32_t* list = &pool_[start_[u]];
    uint32_t kept = 0, count = 0;
    for (uint32_t i = 0; i < size_[u]; i++) {
      const uint32_t t = list[i];
      if (!alive_[t]) continue;
      list[kept++] = t;
      count = appendOthers(u, t, stamp, out.data(), count);
    }
    out.resize(count);
    size_[u] = kept;
    return stamp;
  }

  // Appends to found[count..] the corners of triangle t other than u that do not hold `stamp` yet, in
  // corner order, and stamps them; returns the new count. Which corner u is and whether a neighbour was
  // met before are both unpredictable, so neither is a branch. u itself must hold the stamp already or
  // not be met twice (a triangle never holds a vertex twice).
  uint32_t appendOthers(uint32_t u, uint32_t t, uint32_t stamp, uint32_t* found, uint32_t count) {
    static constexpr uint8_t kFirst[3] = {1, 0, 0}, kSecond[3] = {2, 2, 1};
    const uint32_t* x = &tri_[3 * t];
    const uint32_t k = uint32_t(x[1] == u) + 2 * uint32_t(x[2] == u);
    for (const uint32_t w : {x[kFirst[k]], x[kSecond[k]]}) {
      found[count] = w;
      count += seen_[w] != stamp;
      seen_[w] = stamp;
    }
    return count;
  }

  void append(uint32_t v, uint32_t t) {
    if (size_[v] == capacity_[v]) {
      uint32_t moved = uint32_t(pool_.size());
      capacity_[v] = capacity_[v] * 2 + 4;
      pool_.resize(pool_.size() + capacity_[v]);
      std::copy(pool_.begin() + start_[v], pool_.begin() + start_[v] + size_[v], pool_.begin() + moved);
      start_[v] = moved;
    }
    pool_[start_[v] + size_[v]++] = t;
  }
  // Live and dead triangles of v; callers skip the dead.
  const uint32_t* trianglesOf(uint32_t v) const { return &pool_[start_[v]]; }

  // Enters u's cheapest collapse in the heap, or takes u out when it has none.
  void pushBest(uint32_t u) {
    const Candidate c = bestCandidate(u);
    if (c.to != UINT32_MAX)
      heap_.set(u, c.cost);
    else
      heap_.remove(u);
  }

  // u's cheapest collapse (to UINT32_MAX when it has none), noted as its live candidate. Candidates
  // come straight from u's triangles, each neighbour once; ties go to the lower vertex id, so the
  // order they are met in does not matter.
  Candidate bestCandidate(uint32_t u) {
    if (kind_[u] == kLocked) return {0.0, u, UINT32_MAX};
    const uint32_t stamp = nextStamp();
    seen_[u] = stamp;
    scratchC_.resize(2 * size_t(size_[u]));
    uint32_t* found = scratchC_.data();
    uint32_t count = 0;
    for (uint32_t i = 0; i < size_[u]; i++) {
      const uint32_t t = trianglesOf(u)[i];
      if (alive_[t]) count = appendOthers(u, t, stamp, found, count);
    }
    const bool open = kind_[u] == kOpen;
    const std::vector<uint32_t>& rejected = rejected_[u];
    const Quadric& q = quadric_[u];
    double best = INFINITY;
    uint32_t target = UINT32_MAX;
    for (uint32_t j = 0; j < count; j++) {
      const uint32_t v = found[j];
      if (!rejected.empty() && std::find(rejected.begin(), rejected.end(), v) != rejected.end()) continue;
      if (open && !onOneTriangle(u, v)) continue;  // an open vertex moves along the boundary only
      const double cost = q.meanSquaredDistance(p_[v], quadric_[v], selfCost_[v]);
      const bool better = cost < best || (cost == best && v < target);
      best = better ? cost : best;
      target = better ? v : target;
    }
    bestTarget_[u] = target;
    return {best, u, target};
  }

  // Whether edge uv has exactly one live triangle (a boundary edge).
  bool onOneTriangle(uint32_t u, uint32_t v) const {
    int count = 0;
    for (uint32_t i = 0; i < size_[u]; i++) {
      uint32_t t = trianglesOf(u)[i];
      if (alive_[t] && (tri_[3 * t] == v || tri_[3 * t + 1] == v || tri_[3 * t + 2] == v)) count++;
    }
    return count == 1;
  }

  bool valid(uint32_t u, uint32_t v) {
    // Link condition: common neighbours == apexes of the triangles on edge uv. v's neighbours are
    // stamped last: a neighbour of u with that stamp is common.
    neighbours(u, scratchA_);
    const uint32_t ofV = neighbours(v, scratchB_);
    size_t common = 0;
    for (uint32_t w : scratchA_) common += seen_[w] == ofV;
    // One pass over u's triangles (all live: neighbours dropped the dead): those on edge uv give the
    // apexes, the others must not flip or become degenerate.
    size_t apexes = 0;
    for (uint32_t i = 0; i < size_[u]; i++) {
      const uint32_t* x = &tri_[3 * trianglesOf(u)[i]];
      if (x[0] == v || x[1] == v || x[2] == v) {
        apexes++;
        uint32_t apex = x[0] != u && x[0] != v ? x[0] : x[1] != u && x[1] != v ? x[1] : x[2];
        if (seen_[apex] != ofV) return false;
        continue;
      }
      glm::dvec3 before[3], after[3];
      for (int k = 0; k < 3; k++) {
        before[k] = p_[x[k]];
        after[k] = x[k] == u ? p_[v] : p_[x[k]];
      }
      glm::dvec3 n0 = glm::cross(before[1] - before[0], before[2] - before[0]);
      glm::dvec3 n1 = glm::cross(after[1] - after[0], after[2] - after[0]);
      double l0 = glm::length(n0), l1 = glm::length(n1);
      if (l1 <= 1e-12 * (glm::dot(after[1] - after[0], after[1] - after[0]) +
                         glm::dot(after[2] - after[0], after[2] - after[0])))
        return false;
      if (l0 > 0.0 && glm::dot(n0, n1) < 0.2 * l0 * l1) return false;
    }
    if (apexes == 0 || common != apexes) return false;
    // Chords: new edges v-w between two locked vertices.
    if (kind_[v] == kLocked)
      for (uint32_t w : scratchA_)
        if (w != v && kind_[w] == kLocked && seen_[w] != ofV && !chordAllowed_(v, w)) return false;
    return true;
  }

  // Collapses u onto v, right after valid(u, v) (which left u's neighbours in scratchA_).
  void collapse(uint32_t u, uint32_t v) {
    for (uint32_t i = 0; i < size_[u]; i++) {
      uint32_t t = trianglesOf(u)[i];
      if (!alive_[t]) continue;
      uint32_t* x = &tri_[3 * t];
      if (x[0] == v || x[1] == v || x[2] == v) {
        alive_[t] = 0;
        aliveCount_--;
        continue;
      }
      for (int k = 0; k < 3; k++)
        if (x[k] == u) x[k] = v;
      append(v, t);
    }
    size_[u] = 0;
    removed_[u] = 1;
    collapsedInto_[u] = v;
    quadric_[v].add(quadric_[u]);
    selfCost_[v] = quadric_[v].evaluate(p_[v]);
    // All of v's candidates changed; a neighbour's only if it was aiming at u or v (its other candidates
    // keep their cost, and its collapse onto v only got dearer by v's grown quadric, or so little
    // cheaper that the order barely changes). Validity is checked again when a candidate is popped.
    for (uint32_t w : scratchA_) {
      if (w == u || w == v || (bestTarget_[w] != u && bestTarget_[w] != v)) continue;
      rejected_[w].clear();
      pushBest(w);
    }
    rejected_[v].clear();
    pushBest(v);
  }

  std::vector<uint32_t> tri_;
  std::vector<glm::dvec3> p_;
  std::vector<uint8_t> kind_;
  std::function<bool(uint32_t, uint32_t)> chordAllowed_;
  std::vector<uint8_t> alive_, removed_;
  std::vector<uint32_t> collapsedInto_;
  size_t aliveCount_ = 0;
  std::vector<uint32_t> pool_, start_, size_, capacity_;
  std::vector<Quadric> quadric_;
  std::vector<double> selfCost_;  // quadric_[v].evaluate(p_[v])
  std::vector<uint32_t> seen_;    // the neighbours met by the latest bestCandidate or neighbours call
  uint32_t stamp_ = 0;
  std::vector<uint32_t> bestTarget_;  // target of each vertex's heap entry
  std::vector<std::vector<uint32_t>> rejected_;
  CandidateHeap heap_;
  std::vector<uint32_t> scratchA_, scratchB_, scratchC_;
  double maxCost_ = 0.0;
};

}  // namespace

SimplifiedGroup simplifyGroup(const std::vector<uint32_t>& indices, const std::vector<glm::vec3>& positions,
                              const std::function<bool(uint32_t, uint32_t)>& chordAllowed,
                              const std::vector<uint64_t>& openEdges, size_t targetTriangles) {
  std::vector<uint32_t> globals, local;
  localIds(indices, globals, local);

  // Locked: vertices on an edge with one triangle in the group that another cluster has (the group
  // border); open: vertices on edges of the surface's open boundary and on no locked edge.
  std::vector<uint8_t> kind(globals.size(), kFree);
  std::vector<uint64_t> localOpen;
  for (const uint64_t edge : edgesUsedOnceDense(local, uint32_t(globals.size()))) {
    const uint32_t a = uint32_t(edge >> 32), b = uint32_t(edge);
    const uint64_t global = undirectedEdge(globals[a], globals[b]);
    if (std::binary_search(openEdges.begin(), openEdges.end(), global)) {
      localOpen.push_back(edge);
      for (uint32_t v : {a, b})
        if (kind[v] == kFree) kind[v] = kOpen;
    } else {
      kind[a] = kind[b] = kLocked;
    }
  }

  std::vector<glm::dvec3> points(globals.size());
  glm::dvec3 lower(INFINITY), upper(-INFINITY);
  for (size_t i = 0; i < globals.size(); i++) {
    points[i] = glm::dvec3(positions[globals[i]]);
    lower = glm::min(lower, points[i]);
    upper = glm::max(upper, points[i]);
  }
  const size_t triangles = indices.size() / 3;
  Simplifier s(std::move(local), std::move(points), std::move(kind), localOpen,
               [&](uint32_t a, uint32_t b) { return chordAllowed(globals[a], globals[b]); });
  double error = s.run(targetTriangles);
  error = std::max(error, s.removedVertexError());
  SimplifiedGroup result;
  result.error = float(error);
  // Nothing left is no halving: a group must produce a cluster (a group of loose triangles, whose
  // open edges all collapse, can simplify to none).
  result.halved = s.triangleCount() > 0 && s.triangleCount() <= size_t(float(triangles) * kHalvedRatio);
  result.relaxation = error > kBoundedError * glm::distance(lower, upper) ? 1 : 0;
  result.indices = s.triangles();
  result.globals = std::move(globals);
  return result;
}

}  // namespace vgeo
