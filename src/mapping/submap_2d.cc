#include "fusemap/mapping/submap_2d.h"

#include <cassert>
#include <cstdio>
#include <utility>

#include "fusemap/mapping/deflated_cells.h"

namespace fusemap {
namespace mapping {
namespace {

constexpr int kInitialSubmapCells = 100;

MapLimits InitialLimits(const Eigen::Vector2f& centre_m, double resolution_m) {
  MapLimits limits;
  limits.resolution_m = resolution_m;
  limits.num_x_cells = kInitialSubmapCells;
  limits.num_y_cells = kInitialSubmapCells;
  limits.origin_m =
      centre_m.cast<double>() - 0.5 * kInitialSubmapCells * resolution_m * Eigen::Vector2d::Ones();
  return limits;
}

}  // namespace

constexpr double SubmapsOptions::kMinResolutionM;
constexpr double SubmapsOptions::kMaxResolutionM;
constexpr int SubmapsOptions::kMaxNumRangeData;

void SubmapsOptions::Check(common::OptionChecker* check) const {
  check->Require(num_range_data >= 1 && num_range_data <= kMaxNumRangeData, "num_range_data",
                 "must lie in [1, " + std::to_string(kMaxNumRangeData) + "]");
  char range[64];
  std::snprintf(range, sizeof(range), "must lie in [%g, %g]", kMinResolutionM, kMaxResolutionM);
  check->Require(resolution_m >= kMinResolutionM && resolution_m <= kMaxResolutionM,
                 "resolution_m", range);
  check->Nested("range_data_inserter", range_data_inserter);
}

bool SubmapsOptions::IsValid(std::string* error) const {
  return common::IsValidOptions(*this, error);
}

SubmapsOptions ParseSubmapsOptions(common::ConfigReader& reader) {
  SubmapsOptions options;
  reader.Get("num_range_data", &options.num_range_data);
  reader.Get("resolution_m", &options.resolution_m);
  options.range_data_inserter =
      ParseProbabilityGridRangeDataInserterOptions(reader.Child("range_data_inserter"));
  reader.CheckOptions(options);
  return options;
}

Submap2D::Submap2D(const Eigen::Vector2f& origin_in_local_m, double resolution_m)
    : T_local_submap_(common::Rigid2d::Translation(origin_in_local_m.cast<double>())),
      grid_(std::make_shared<ProbabilityGrid>(InitialLimits(origin_in_local_m, resolution_m))) {}

Submap2D::Submap2D(const SubmapState2D& state)
    : T_local_submap_(state.T_local_submap),
      num_range_data_(state.num_range_data),
      finished_(state.finished),
      grid_(std::make_shared<ProbabilityGrid>(state.limits, state.cells)) {}

std::shared_ptr<const ProbabilityGrid> Submap2D::grid() const {
  {
    std::lock_guard<std::mutex> lock(storage_mutex_);
    if (grid_) return grid_;
  }
  // Compacted: deflated_cells_ and compact_limits_ never change again, so they are read
  // without the lock, and grid_bytes() (health, under global SLAM's lock) never waits for
  // an inflation.
  std::vector<uint16_t> cells;
  const size_t num_cells =
      static_cast<size_t>(compact_limits_.num_x_cells) * compact_limits_.num_y_cells;
  const bool inflated = InflateCells(deflated_cells_, num_cells, &cells);
  // Made by DeflateCells in this process from exactly these cells.
  assert(inflated);
  (void)inflated;
  return std::make_shared<ProbabilityGrid>(compact_limits_, std::move(cells));
}

size_t Submap2D::grid_bytes() const {
  std::lock_guard<std::mutex> lock(storage_mutex_);
  return grid_ ? grid_->bytes() : deflated_cells_.capacity();
}

void Submap2D::Compact() const {
  assert(finished_);
  std::shared_ptr<const ProbabilityGrid> grid;
  {
    std::lock_guard<std::mutex> lock(storage_mutex_);
    if (!grid_) return;
    grid = grid_;
  }
  // Deflated outside the lock: the cells of a finished submap do not change, and readers need
  // not wait the tens of milliseconds a large grid takes.
  std::vector<uint8_t> deflated;
  if (!DeflateCells(grid->cells(), &deflated)) return;  // out of memory: stays as it is
  std::lock_guard<std::mutex> lock(storage_mutex_);
  if (!grid_) return;  // another thread compacted it meanwhile
  compact_limits_ = grid_->limits();
  deflated_cells_ = std::move(deflated);
  grid_.reset();
}

bool Submap2D::compacted() const {
  std::lock_guard<std::mutex> lock(storage_mutex_);
  return !grid_;
}

SubmapState2D Submap2D::ExportState() const {
  SubmapState2D state;
  state.T_local_submap = T_local_submap_;
  const std::shared_ptr<const ProbabilityGrid> grid = this->grid();
  state.limits = grid->limits();
  state.cells = grid->cells();
  state.num_range_data = num_range_data_;
  state.finished = finished_;
  return state;
}

void Submap2D::InsertRangeData(const sensor::RangeData& range_data_in_local,
                               const RangeDataInserter2D& inserter) {
  assert(!finished_);
  // Unfinished submaps are never compacted, and only this thread writes them.
  const bool inserted = inserter.Insert(range_data_in_local, grid_.get());
  assert(inserted);
  (void)inserted;
  ++num_range_data_;
}

namespace {

bool LimitsCanHold(const MapLimits& limits, const sensor::RangeData& range_data) {
  Eigen::Vector2f min_m, max_m;
  return RangeDataBounds(range_data, &min_m, &max_m) &&
         ProbabilityGrid::LimitsCovering(limits, min_m, max_m).has_value();
}

}  // namespace

bool Submap2D::CanInsert(const sensor::RangeData& range_data_in_local) const {
  return LimitsCanHold(grid()->limits(), range_data_in_local);
}

void Submap2D::Finish() {
  assert(!finished_);
  auto cropped = std::make_shared<ProbabilityGrid>(grid_->Cropped());
  std::lock_guard<std::mutex> lock(storage_mutex_);
  grid_ = std::move(cropped);
  finished_ = true;
}

ActiveSubmaps2D::ActiveSubmaps2D(const SubmapsOptions& options)
    : options_(options), inserter_(options.range_data_inserter) {
  std::string error;
  assert(options.IsValid(&error));
}

std::vector<std::shared_ptr<const Submap2D>> ActiveSubmaps2D::InsertRangeData(
    const sensor::RangeData& range_data_in_local) {
  const bool start_new = submaps_.empty() || submaps_.back()->num_range_data() == options_.num_range_data;
  // With a new submap the finished front one leaves and does not take the data.
  for (size_t i = start_new && submaps_.size() >= 2 ? 1 : 0; i < submaps_.size(); ++i) {
    if (!submaps_[i]->CanInsert(range_data_in_local)) return {};
  }
  if (start_new) {
    if (!LimitsCanHold(InitialLimits(range_data_in_local.origin, options_.resolution_m), range_data_in_local)) {
      return {};
    }
    AddSubmap(range_data_in_local.origin);
  }
  for (const auto& submap : submaps_) submap->InsertRangeData(range_data_in_local, inserter_);
  if (submaps_.front()->num_range_data() == 2 * options_.num_range_data) {
    submaps_.front()->Finish();
  }
  return submaps();
}

std::vector<std::shared_ptr<const Submap2D>> ActiveSubmaps2D::submaps() const {
  return std::vector<std::shared_ptr<const Submap2D>>(submaps_.begin(), submaps_.end());
}

void ActiveSubmaps2D::Restore(std::vector<std::shared_ptr<Submap2D>> submaps) {
  assert(submaps_.empty() && submaps.size() <= 2);
  submaps_ = std::move(submaps);
}

void ActiveSubmaps2D::AddSubmap(const Eigen::Vector2f& origin_in_local_m) {
  if (submaps_.size() >= 2) {
    // Only the finished older submap leaves; the caller saw it finished on the last call.
    assert(submaps_.front()->finished());
    submaps_.erase(submaps_.begin());
  }
  submaps_.push_back(std::make_shared<Submap2D>(origin_in_local_m, options_.resolution_m));
}

}  // namespace mapping
}  // namespace fusemap
