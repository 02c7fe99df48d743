#ifndef FUSEMAP_MAPPING_DEFLATED_CELLS_H_
#define FUSEMAP_MAPPING_DEFLATED_CELLS_H_

#include <cstddef>
#include <cstdint>
#include <vector>

namespace fusemap {
namespace mapping {

// Lossless in-memory storage of a finished grid's 2-byte cells (zlib). Outdoors a finished
// submap spans the bounding box of 30 m rays and holds megabytes of cells, most of them
// unknown or free at one of a few saturated values; a long run keeps every one of them.
// The high bytes are stored before the low bytes: they take few values and deflate to almost
// nothing that way.
// False only if zlib cannot allocate its state; the caller then keeps the cells as they are.
bool DeflateCells(const std::vector<uint16_t>& cells, std::vector<uint8_t>* deflated);

// The cells DeflateCells() was given; `num_cells` is their count. False if `deflated` does not
// hold exactly that many (it was not made by DeflateCells).
bool InflateCells(const std::vector<uint8_t>& deflated, size_t num_cells,
                  std::vector<uint16_t>* cells);

}  // namespace mapping
}  // namespace fusemap

#endif  // FUSEMAP_MAPPING_DEFLATED_CELLS_H_
