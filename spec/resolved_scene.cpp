#include "spec/resolved_scene.h"

#include <algorithm>
#include <cstdio>
#include <optional>

#include "spec/scene_keys.h"

namespace hairfit {

namespace fs = std::filesystem;

namespace {

// Values start in this column and comments after them in kCommentColumn, so that the file reads as
// a table and a changed value shows as one changed line under git.
constexpr std::size_t kCommentColumn = 40;

const char* const kHeader =
    "# The scene as hairfit resolved it for the run whose outputs lie beside this file: every key\n"
    "# with the value used, and after it where that value came from:\n"
    "#   FILE:LINE        the scene file, at that line\n"
    "#   preset \"NAME\"    the accuracy preset the scene names\n"
    "#   shell default    hair that suits its shell (hair.length and hair.tilt unset)\n"
    "#   default          the documented default (spec/reference.md)\n"
    "#   derived: ...     worked out at run time, from the figure given; the key stays commented\n"
    "#                    out (unset), so that running this file derives it again\n"
    "# Paths are relative to this file's folder. `hairfit run` on this file gives the same outputs\n"
    "# byte for byte; pin a key by copying its line into your scene.\n";
const char* const kShellNote =
    "# Pinning hair.length or hair.tilt turns the shell defaults off (spec/reference.md, \"Hair that\n"
    "# suits its shell\"): copy the keys marked \"shell default\" with them.\n";

// A TOML basic string.
std::string quoted(const std::string& text) {
  std::string out = "\"";
  for (const char c : text) {
    const auto byte = static_cast<unsigned char>(c);
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (byte < 0x20 || byte == 0x7f) {
      char escape[8];
      std::snprintf(escape, sizeof escape, "\\u%04X", byte);
      out += escape;
    } else {
      out += c;
    }
  }
  return out + '"';
}

// A comment stays on its line.
std::string one_line(std::string text) {
  std::replace(text.begin(), text.end(), '\n', ' ');
  std::replace(text.begin(), text.end(), '\r', ' ');
  return text;
}

fs::path normal_folder(const fs::path& folder) {
  fs::path f = fs::absolute(folder).lexically_normal();
  return f.filename().empty() ? f.parent_path() : f;
}

// `path` (absolute) as the parser resolves it again from a file in `folder`: relative where the two
// share a folder below the root and that gives the same path back, absolute otherwise.
std::string path_text(const fs::path& path, const fs::path& folder) {
  const fs::path relative = path.lexically_relative(folder);
  const auto ups = std::count(relative.begin(), relative.end(), fs::path(".."));
  const fs::path below_root = folder.relative_path();
  const auto depth = std::distance(below_root.begin(), below_root.end());
  const bool same = !relative.empty() && ups < depth && (folder / relative).lexically_normal() == path;
  return quoted((same ? relative : path).generic_string());
}

std::string table_of(const std::string& key) {
  const std::size_t dot = key.rfind('.');
  return dot == std::string::npos ? std::string() : key.substr(0, dot);
}

std::string leaf_of(const std::string& key) { return key.substr(key.rfind('.') + 1); }

class Writer {
 public:
  Writer(const Scene& scene, const std::vector<DerivedKey>& derived, const fs::path& folder)
      : scene_(scene), derived_(derived), folder_(normal_folder(folder)) {}

  std::string text() {
    out_ = kHeader;
    if (scene_.hair.from_shell) out_ += kShellNote;
    out_ += "# Resolved from " + one_line(path_text(scene_.file, folder_)) + ".\n";
    for (const std::string& table : tables()) {
      if (!table.empty()) out_ += "\n[" + table + "]\n";
      for (const SceneKey& k : scene_keys())
        if (table_of(k.name) == table) write_key(k);
    }
    return out_;
  }

 private:
  // The tables in the order of their first key, the top level first.
  static std::vector<std::string> tables() {
    std::vector<std::string> out{""};
    for (const SceneKey& k : scene_keys())
      if (std::find(out.begin(), out.end(), table_of(k.name)) == out.end()) out.push_back(table_of(k.name));
    return out;
  }

  void write_key(const SceneKey& k) {
    const std::string leaf = leaf_of(k.name);
    std::vector<const DerivedKey*> derived;
    for (const DerivedKey& d : derived_)
      if (d.key == k.name) derived.push_back(&d);
    const std::optional<std::string> value = value_text(k);
    if (!value) return line("# " + leaf + ": unset", source(k));
    if (!left_unset(k)) {
      line(leaf + " = " + *value, source(k));
      for (const DerivedKey* d : derived)
        line("#   at run time: " + one_line(d->value), "derived: " + d->source);
      return;
    }
    for (const DerivedKey* d : derived)
      line("# " + leaf + " = " + one_line(d->value), "derived: " + d->source);
    if (derived.empty())
      line("# " + leaf + ": unset", "derived: the roots stage derives it from the shell at run time");
  }

  // The keys whose absence makes the run derive the hair from the shell stay unset.
  bool left_unset(const SceneKey& k) const {
    return scene_.hair.from_shell &&
           std::find(kShellTriggerKeys.begin(), kShellTriggerKeys.end(), k.name) != kShellTriggerKeys.end();
  }

  // The key's value as TOML text; none for an optional file the scene does not name.
  std::optional<std::string> value_text(const SceneKey& k) const {
    if (k.name == "format") return quoted(scene_.format);
    if (k.name == "output.dir") return quoted(".");
    if (k.kind == KeyKind::path) {
      const std::optional<fs::path> path = file_of(k.name);
      if (!path) return std::nullopt;
      return path_text(*path, folder_);
    }
    if (k.kind == KeyKind::vector3) {
      const auto written = scene_.directions_as_written.find(k.name);
      if (written != scene_.directions_as_written.end()) {
        const Vec3& v = written->second;
        return "[" + number_text(v.x()) + ", " + number_text(v.y()) + ", " + number_text(v.z()) + "]";
      }
    }
    return k.show(scene_);
  }

  std::optional<fs::path> file_of(const std::string& key) const {
    if (key == "inputs.scalp") return scene_.inputs.scalp;
    if (key == "inputs.volume") return scene_.inputs.volume;
    if (key == "maps.density") return scene_.maps.density;
    if (key == "maps.tilt") return scene_.maps.tilt;
    if (key == "maps.length") return scene_.maps.length;
    if (key == "output.occluder") return scene_.output.occluder;
    throw std::logic_error("resolved scene: no file behind path key " + key);
  }

  std::string source(const SceneKey& k) const {
    if (k.name == "output.dir" && normal_folder(scene_.output.dir) != folder_) return "hairfit run --out";
    const auto at = scene_.locations.find(k.name);
    if (at != scene_.locations.end()) return scene_.file.filename().string() + ":" + std::to_string(at->second.line);
    const auto rule = scene_.implied.find(k.name);
    if (rule != scene_.implied.end()) return rule->second;
    return "default";
  }

  void line(const std::string& text, const std::string& comment) {
    out_ += text;
    out_ += std::string(text.size() < kCommentColumn ? kCommentColumn - text.size() : 1, ' ');
    out_ += "# " + one_line(comment) + "\n";
  }

  const Scene& scene_;
  const std::vector<DerivedKey>& derived_;
  const fs::path folder_;
  std::string out_;
};

}  // namespace

std::string resolved_scene_text(const Scene& scene, const std::vector<DerivedKey>& derived, const fs::path& folder) {
  return Writer(scene, derived, folder).text();
}

}  // namespace hairfit
