// Bundles (see bundles.hpp).
#include "bundle/bundles.hpp"

#include <algorithm>
#include <limits>
#include <span>

namespace globe {

namespace {

constexpr uint32_t kNone = std::numeric_limits<uint32_t>::max();

}  // namespace

BundleSet make_bundles(const ReducedGraph& g, const std::vector<std::vector<uint32_t>>& routes,
                       const std::vector<double>& weights) {
  const size_t edges = g.edges.size();
  // Each edge's connections (CSR, in connection order).
  std::vector<uint32_t> offsets(edges + 1, 0);
  for (const auto& r : routes)
    for (uint32_t e : r)
      ++offsets[e + 1];
  for (size_t e = 0; e < edges; ++e)
    offsets[e + 1] += offsets[e];
  std::vector<uint32_t> members(offsets[edges]);
  {
    std::vector<uint32_t> at(offsets.begin(), offsets.end() - 1);
    for (uint32_t c = 0; c < routes.size(); ++c)
      for (uint32_t e : routes[c])
        members[at[e]++] = c;
  }
  auto set_of = [&](uint32_t e) {
    return std::span<const uint32_t>(members.data() + offsets[e], offsets[e + 1] - offsets[e]);
  };
  auto same_set = [&](uint32_t a, uint32_t b) {
    const auto sa = set_of(a), sb = set_of(b);
    return std::equal(sa.begin(), sa.end(), sb.begin(), sb.end());
  };

  // Links: at a node, two used edges with the same set continue each other.
  // (A connection's path is simple: it enters and leaves a node at most
  // once, so no third edge there can carry the same set.)
  struct Links {
    uint32_t edge[2] = {kNone, kNone};
  };
  std::vector<Links> links(edges);
  auto link = [&](uint32_t a, uint32_t b) {
    for (uint32_t* slot : {&links[a].edge[0], &links[a].edge[1]})
      if (*slot == kNone) {
        *slot = b;
        break;
      }
  };
  std::vector<uint32_t> used;
  for (uint32_t v = 0; v + 1 < g.offsets.size(); ++v) {
    used.clear();
    for (uint32_t k = g.offsets[v]; k < g.offsets[v + 1]; ++k) {
      const uint32_t e = g.incident[k];
      if (offsets[e + 1] > offsets[e] && g.edges[e].a != g.edges[e].b) used.push_back(e);
    }
    for (size_t i = 0; i < used.size(); ++i)
      for (size_t j = i + 1; j < used.size(); ++j)
        if (same_set(used[i], used[j])) {
          link(used[i], used[j]);
          link(used[j], used[i]);
        }
  }

  BundleSet out;
  out.paths.resize(routes.size());
  std::vector<uint32_t> bundle_of(edges, kNone);
  auto other_end = [&](uint32_t e, uint32_t node) {
    return g.edges[e].a == node ? g.edges[e].b : g.edges[e].a;
  };
  // Appends edge e, walked from reduced node `from`, to the bundle's nodes.
  auto append = [&](Bundle& b, uint32_t e, uint32_t from) {
    const ReducedGraph::Edge& edge = g.edges[e];
    const auto chain = std::span<const uint32_t>(g.path.data() + edge.first, edge.count);
    const bool forward = edge.a == from;
    for (size_t i = b.nodes.empty() ? 0 : 1; i < chain.size(); ++i)
      b.nodes.push_back(forward ? chain[i] : chain[chain.size() - 1 - i]);
    b.length_m += edge.length_m;
  };
  auto walk = [&](uint32_t start, uint32_t from) {
    const uint32_t id = static_cast<uint32_t>(out.bundles.size());
    Bundle b;
    uint32_t e = start, node = from, prev = kNone;
    while (e != kNone && bundle_of[e] == kNone) {
      bundle_of[e] = id;
      append(b, e, node);
      node = other_end(e, node);
      uint32_t next = kNone;
      for (uint32_t cand : links[e].edge)
        if (cand != kNone && cand != prev && bundle_of[cand] == kNone &&
            (g.edges[cand].a == node || g.edges[cand].b == node))
          next = cand;
      prev = e;
      e = next;
    }
    for (uint32_t c : set_of(start)) {
      b.weight += weights[c];
      ++b.count;
    }
    out.bundles.push_back(std::move(b));
  };
  // Chains start at an edge with an end not linked on (in edge order), so
  // each bundle is numbered by its first edge. An edge's link at node v is
  // the linked edge that touches v.
  auto linked_at = [&](uint32_t e, uint32_t node) {
    for (uint32_t cand : links[e].edge)
      if (cand != kNone && (g.edges[cand].a == node || g.edges[cand].b == node)) return true;
    return false;
  };
  for (uint32_t e = 0; e < edges; ++e) {
    if (bundle_of[e] != kNone || offsets[e + 1] == offsets[e] || g.edges[e].a == g.edges[e].b)
      continue;
    const uint32_t a = g.edges[e].a, b = g.edges[e].b;
    if (!linked_at(e, a))
      walk(e, a);
    else if (!linked_at(e, b))
      walk(e, b);
  }
  // What is left is linked at both ends all round: a cycle (not made by
  // simple paths, but kept safe).
  for (uint32_t e = 0; e < edges; ++e)
    if (bundle_of[e] == kNone && offsets[e + 1] > offsets[e] && g.edges[e].a != g.edges[e].b)
      walk(e, g.edges[e].a);

  for (uint32_t c = 0; c < routes.size(); ++c)
    for (uint32_t e : routes[c])
      if (out.paths[c].empty() || out.paths[c].back() != bundle_of[e])
        out.paths[c].push_back(bundle_of[e]);
  return out;
}

}  // namespace globe
