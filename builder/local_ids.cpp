// local_ids.cpp: a group's or cluster's vertices renumbered 0..n-1 in order of first use, so that the
// steps working on it (simplify.cpp, cluster.cpp) size their arrays by its own vertices. A hash table
// of the list's size maps global ids to local ones: an array over all of the mesh's vertices, kept by
// each thread, cost memory in proportion to the threads.
#include "builder.h"

namespace vgeo {

namespace {

size_t tableSizeFor(size_t indices) {
  size_t size = 64;
  while (size < 2 * indices) size *= 2;
  return size;
}

size_t slotOf(uint32_t id, size_t tableSize) {
  return size_t((uint64_t(id) * 0x9e3779b97f4a7c15ull) >> 32) & (tableSize - 1);
}

}  // namespace

void localIds(const std::vector<uint32_t>& indices, std::vector<uint32_t>& globals, std::vector<uint32_t>& local) {
  const size_t tableSize = tableSizeFor(indices.size());
  std::vector<uint32_t> table(tableSize, UINT32_MAX);  // local ids; globals[id] is the key
  globals.clear();
  local.resize(indices.size());
  for (size_t i = 0; i < indices.size(); i++) {
    size_t h = slotOf(indices[i], tableSize);
    while (table[h] != UINT32_MAX && globals[table[h]] != indices[i]) h = (h + 1) & (tableSize - 1);
    if (table[h] == UINT32_MAX) {
      table[h] = uint32_t(globals.size());
      globals.push_back(indices[i]);
    }
    local[i] = table[h];
  }
}

size_t distinctCount(const std::vector<uint32_t>& indices) {
  const size_t tableSize = tableSizeFor(indices.size());
  thread_local std::vector<uint32_t> table;  // the ids themselves; UINT32_MAX is never an index
  table.assign(tableSize, UINT32_MAX);
  size_t count = 0;
  for (const uint32_t id : indices) {
    size_t h = slotOf(id, tableSize);
    while (table[h] != UINT32_MAX && table[h] != id) h = (h + 1) & (tableSize - 1);
    if (table[h] == UINT32_MAX) table[h] = id, count++;
  }
  return count;
}

}  // namespace vgeo
