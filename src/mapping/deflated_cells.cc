#include "fusemap/mapping/deflated_cells.h"

#include <zlib.h>

namespace fusemap {
namespace mapping {

bool DeflateCells(const std::vector<uint16_t>& cells, std::vector<uint8_t>* deflated) {
  const size_t n = cells.size();
  std::vector<uint8_t> planes(2 * n);
  for (size_t i = 0; i < n; ++i) {
    planes[i] = static_cast<uint8_t>(cells[i] >> 8);
    planes[n + i] = static_cast<uint8_t>(cells[i] & 0xff);
  }
  uLongf size = compressBound(planes.size());
  deflated->resize(size);
  // Level 1: compaction runs once per finished submap, inflation at every precomputation and
  // map drawing; higher levels gain little on grids at several times the cost.
  if (compress2(deflated->data(), &size, planes.data(), planes.size(), 1) != Z_OK) return false;
  deflated->resize(size);
  deflated->shrink_to_fit();
  return true;
}

bool InflateCells(const std::vector<uint8_t>& deflated, size_t num_cells,
                  std::vector<uint16_t>* cells) {
  std::vector<uint8_t> planes(2 * num_cells);
  uLongf size = planes.size();
  const int rc = uncompress(planes.data(), &size, deflated.data(), deflated.size());
  if (rc != Z_OK || size != planes.size()) return false;
  cells->resize(num_cells);
  for (size_t i = 0; i < num_cells; ++i) {
    (*cells)[i] = static_cast<uint16_t>(planes[i] << 8 | planes[num_cells + i]);
  }
  return true;
}

}  // namespace mapping
}  // namespace fusemap
