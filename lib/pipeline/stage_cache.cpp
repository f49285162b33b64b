#include "pipeline/stage_cache.h"

#include <algorithm>
#include <cstring>
#include <fstream>
#include <vector>

#include "core/digest.h"
#include "io/atomic_file.h"
#include "pipeline/byte_stream.h"

namespace hairfit {

namespace fs = std::filesystem;

namespace {

constexpr char kMagic[8] = {'H', 'A', 'I', 'R', 'F', 'I', 'T', 'C'};

std::uint64_t payload_digest(std::string_view payload) { return Digest().add_bytes(payload.data(), payload.size()).value(); }

}  // namespace

fs::path StageCache::entry_path(const std::string& stage, const std::string& key) const {
  return folder_ / (stage + "-" + key + ".entry");
}

std::optional<std::string> StageCache::load(const std::string& stage, const std::string& key, std::string& problem) const {
  problem.clear();
  const fs::path path = entry_path(stage, key);
  std::ifstream file(path, std::ios::binary);
  if (!file) return std::nullopt;
  std::string bytes((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
  try {
    ByteReader in(bytes);
    char magic[8];
    in.raw(magic, sizeof magic);
    if (std::memcmp(magic, kMagic, sizeof magic) != 0) throw CodecError("not a hairfit cache entry");
    const auto version = in.get<std::uint32_t>();
    if (version != kCacheFormatVersion)
      throw CodecError("cache format " + std::to_string(version) + ", this build reads " + std::to_string(kCacheFormatVersion));
    std::string stored_key(in.get<std::uint32_t>(), '\0');
    if (stored_key.size() > 256) throw CodecError("impossible key length");
    in.raw(stored_key.data(), stored_key.size());
    if (stored_key != key) throw CodecError("holds the value of another key (" + stored_key + ")");
    const auto length = in.get<std::uint64_t>();
    const auto checksum = in.get<std::uint64_t>();
    if (length != in.remaining())
      throw CodecError("payload of " + std::to_string(in.remaining()) + " bytes, the header says " + std::to_string(length));
    std::string payload = bytes.substr(bytes.size() - length);
    if (payload_digest(payload) != checksum) throw CodecError("payload checksum mismatch (corrupt)");
    return payload;
  } catch (const CodecError& e) {
    problem = path.string() + ": " + e.what();
    return std::nullopt;
  }
}

void StageCache::store(const std::string& stage, const std::string& key, const std::string& payload) const {
  ByteWriter header;
  header.raw(kMagic, sizeof kMagic);
  header.put<std::uint32_t>(kCacheFormatVersion);
  header.put<std::uint32_t>(static_cast<std::uint32_t>(key.size()));
  header.raw(key.data(), key.size());
  header.put<std::uint64_t>(payload.size());
  header.put<std::uint64_t>(payload_digest(payload));
  write_file_atomically(entry_path(stage, key), [&](std::ostream& out) {
    out.write(header.bytes().data(), static_cast<std::streamsize>(header.bytes().size()));
    out.write(payload.data(), static_cast<std::streamsize>(payload.size()));
  });

  // Keep the newest few entries of this stage; a failure to prune never fails the run.
  std::error_code error;
  std::vector<std::pair<fs::file_time_type, fs::path>> entries;
  for (const fs::directory_entry& e : fs::directory_iterator(folder_, error)) {
    const std::string name = e.path().filename().string();
    if (name.rfind(stage + "-", 0) == 0 && e.path().extension() == ".entry")
      entries.emplace_back(e.last_write_time(error), e.path());
  }
  if (entries.size() <= static_cast<std::size_t>(kEntriesPerStage)) return;
  std::sort(entries.begin(), entries.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
  for (std::size_t i = kEntriesPerStage; i < entries.size(); ++i)
    if (entries[i].second != entry_path(stage, key)) fs::remove(entries[i].second, error);
}

}  // namespace hairfit
