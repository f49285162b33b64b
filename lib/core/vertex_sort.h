// Sorting the records of a mesh's edges (or any records keyed first by a vertex index) in linear
// time: a counting sort on the vertex, then a small sort within each vertex's few records.
#pragma once
#include <algorithm>
#include <vector>

namespace hairfit {

// Sorts `items` by vertex(item), an index in [0, vertex_count), and items of one vertex by `less`:
// the order std::sort would give with the comparison (vertex, then less) when that is a total
// order. A mesh vertex has a handful of edges, so the inner sorts are short.
template <typename T, typename Vertex, typename Less>
void sort_by_vertex(std::vector<T>& items, int vertex_count, Vertex vertex, Less less) {
  std::vector<int> start(static_cast<std::size_t>(vertex_count) + 1, 0);
  for (const T& item : items) ++start[vertex(item) + 1];
  for (int v = 0; v < vertex_count; ++v) start[v + 1] += start[v];
  std::vector<T> sorted(items.size());
  std::vector<int> fill(start.begin(), start.end() - 1);
  for (const T& item : items) sorted[fill[vertex(item)]++] = item;
  for (int v = 0; v < vertex_count; ++v)
    if (start[v + 1] - start[v] > 1) std::sort(sorted.begin() + start[v], sorted.begin() + start[v + 1], less);
  items = std::move(sorted);
}

}  // namespace hairfit
