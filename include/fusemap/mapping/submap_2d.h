#ifndef FUSEMAP_MAPPING_SUBMAP_2D_H_
#define FUSEMAP_MAPPING_SUBMAP_2D_H_

#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "fusemap/common/config_reader.h"
#include "fusemap/common/rigid_transform.h"
#include "fusemap/mapping/probability_grid.h"
#include "fusemap/mapping/range_data_inserter_2d.h"
#include "fusemap/sensor/sensor_types.h"

namespace fusemap {
namespace mapping {

struct SubmapsOptions {
  // Range data per submap before the next one starts; each submap ends up with twice this.
  int num_range_data = 35;
  double resolution_m = 0.05;
  // A grid finer than 5 mm could not hold a laser's range within ProbabilityGrid::kMaxCells;
  // coarser than 1 m maps nothing. More range data per submap than this never finishes one.
  static constexpr double kMinResolutionM = 0.005;
  static constexpr double kMaxResolutionM = 1.0;
  static constexpr int kMaxNumRangeData = 100000;
  ProbabilityGridRangeDataInserterOptions range_data_inserter;

  // Each field's rule, against its key (see common::OptionChecker).
  void Check(common::OptionChecker* check) const;
  // The first problem, as "<key> <why>".
  bool IsValid(std::string* error) const;
};

// Reads num_range_data, resolution_m and the child mapping `range_data_inserter`.
SubmapsOptions ParseSubmapsOptions(common::ConfigReader& reader);

// Everything a submap holds, as plain values (checkpoints).
struct SubmapState2D {
  common::Rigid2d T_local_submap;
  MapLimits limits;
  std::vector<uint16_t> cells;  // as ProbabilityGrid::cells()
  int num_range_data = 0;
  bool finished = false;
};

// A local occupancy map built from consecutive range data. As in Cartographer, the grid is
// expressed in the local SLAM frame (cell coordinates are local coordinates) and
// T_local_submap is a pure translation to the origin at creation. Once finished, a submap's
// cells never change again, so it may be shared read-only with other threads; its storage may
// still change (Compact()), which is why the grid is handed out by shared pointer.
class Submap2D {
 public:
  // Starts an empty grid of 100 x 100 cells centred on `origin_in_local_m`.
  Submap2D(const Eigen::Vector2f& origin_in_local_m, double resolution_m);
  // Restores a submap exactly as ExportState() saw it; `state.cells` must match the limits.
  explicit Submap2D(const SubmapState2D& state);

  Submap2D(const Submap2D&) = delete;
  Submap2D& operator=(const Submap2D&) = delete;

  const common::Rigid2d& T_local_submap() const { return T_local_submap_; }
  // The grid. Of a compacted submap, a copy inflated by this call (a few milliseconds for a
  // large one): keep the pointer while reading rather than calling again. An unfinished
  // submap's grid changes with the next InsertRangeData().
  std::shared_ptr<const ProbabilityGrid> grid() const;
  // Memory the cells take as stored (deflated once compacted).
  size_t grid_bytes() const;
  int num_range_data() const { return num_range_data_; }
  bool finished() const { return finished_; }

  // Must not be called once finished, nor with data the grid cannot cover (CanInsert).
  void InsertRangeData(const sensor::RangeData& range_data_in_local,
                       const RangeDataInserter2D& inserter);
  void Finish();
  // False if the grid would have to grow past ProbabilityGrid::kMaxCells (or the data are not
  // finite) to hold `range_data_in_local`.
  bool CanInsert(const sensor::RangeData& range_data_in_local) const;

  // Finished submaps only: from now on the cells are held deflated (mapping/deflated_cells.h,
  // lossless) and grid() inflates a copy per call. For submaps that are read rarely: global
  // SLAM keeps every finished submap for the whole run but reads one only to build its
  // precomputation grids, to refine a loop closure match, to trim and to draw the map. Any
  // thread may call it while others call grid(); grids handed out before stay valid.
  void Compact() const;
  bool compacted() const;

  SubmapState2D ExportState() const;

 private:
  common::Rigid2d T_local_submap_;
  int num_range_data_ = 0;
  bool finished_ = false;
  // Storage: `grid_` until Compact(), then `deflated_cells_` of a grid with `compact_limits_`.
  // Guarded by the mutex because compaction changes the storage (never the cells) of a submap
  // other threads read.
  mutable std::mutex storage_mutex_;
  mutable std::shared_ptr<ProbabilityGrid> grid_;
  mutable MapLimits compact_limits_;
  mutable std::vector<uint8_t> deflated_cells_;
};

// Cartographer's pair of active submaps: every range data goes into both; when the newer one
// has num_range_data, the older one (then holding 2 * num_range_data) is finished, and on the
// next insertion it is dropped and a new submap starts at that range data's origin. So each
// finished submap overlaps its successor by half, and the front (older) submap, which is the
// more complete, is the one to match against. Unfinished submaps handed out are still written
// by the next InsertRangeData(): only finished ones may be read from another thread.
class ActiveSubmaps2D {
 public:
  explicit ActiveSubmaps2D(const SubmapsOptions& options);

  ActiveSubmaps2D(const ActiveSubmaps2D&) = delete;
  ActiveSubmaps2D& operator=(const ActiveSubmaps2D&) = delete;

  // Inserts into the active submaps and returns them, oldest first. The front one may have
  // just been finished by this call; that is how the caller learns to hand it to global SLAM.
  // Returns nothing and changes nothing if a submap it would go into cannot hold the data
  // (Submap2D::CanInsert): all or nothing.
  std::vector<std::shared_ptr<const Submap2D>> InsertRangeData(
      const sensor::RangeData& range_data_in_local);

  // The current active submaps, oldest first (empty before the first insertion).
  std::vector<std::shared_ptr<const Submap2D>> submaps() const;

  // Replaces the (empty) set of active submaps with restored ones, oldest first (at most two;
  // with two, the front one is the older and more complete one, as InsertRangeData leaves it).
  void Restore(std::vector<std::shared_ptr<Submap2D>> submaps);

 private:
  void AddSubmap(const Eigen::Vector2f& origin_in_local_m);

  SubmapsOptions options_;
  RangeDataInserter2D inserter_;
  std::vector<std::shared_ptr<Submap2D>> submaps_;
};

}  // namespace mapping
}  // namespace fusemap

#endif  // FUSEMAP_MAPPING_SUBMAP_2D_H_
