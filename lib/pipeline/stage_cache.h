// The folder of cached stage values (default `<scene folder>/.hairfit-cache`). One file per stage
// and key, `<stage>-<key>.entry`:
//   magic "HAIRFITC" (8 bytes) · format version (u32) · key length (u32) · key · payload length
//   (u64) · payload digest (u64, core/digest.h) · payload
// An entry is used only if every header field matches and the payload's digest is right, so a
// truncated, corrupt or foreign file (another key, another format) is reported and recomputed,
// never trusted. Entries are written atomically (io/atomic_file.h); concurrent runs at worst
// write the same entry twice. Only the newest kEntriesPerStage entries of a stage are kept.
#pragma once
#include <filesystem>
#include <optional>
#include <string>

namespace hairfit {

inline constexpr std::uint32_t kCacheFormatVersion = 6;  // 2: PreGuides::shared_solves; 3: Guide::point_forces, f5; 4: RootSet::hang_weights; 5: Strands::cut_at_scalp; 6: StageReport::derived
inline constexpr int kEntriesPerStage = 6;

class StageCache {
 public:
  explicit StageCache(std::filesystem::path folder) : folder_(std::move(folder)) {}
  const std::filesystem::path& folder() const { return folder_; }
  std::filesystem::path entry_path(const std::string& stage, const std::string& key) const;

  // The payload stored under (stage, key), or nothing when there is no usable entry; `problem`
  // receives why an existing entry was rejected ("" when there was simply none).
  std::optional<std::string> load(const std::string& stage, const std::string& key, std::string& problem) const;

  // Stores the payload (atomically), then drops the stage's oldest entries beyond kEntriesPerStage.
  void store(const std::string& stage, const std::string& key, const std::string& payload) const;

 private:
  std::filesystem::path folder_;
};

}  // namespace hairfit
