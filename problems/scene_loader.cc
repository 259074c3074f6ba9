#include "problems/scene_loader.h"

#include <cerrno>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "core/input_error.h"
#include "core/input_file.h"
#include "problems/scene_parser.h"

namespace ipstep {
namespace internal {
// Built-in scene name -> JSON text. Defined in builtin_scenes.cc, which
// problems/CMakeLists.txt generates from problems/*.json.
const std::map<std::string, std::string>& BuiltinSceneTexts();
}  // namespace internal

namespace {

using nlohmann::json;

// Upper bound on the size of a scene file (a 1000 x 1000 grid written out as
// explicit nodes and springs takes about 100 MB).
constexpr std::uintmax_t kMaxSceneFileBytes = std::uintmax_t{256} << 20;

// Removes nlohmann's "[json.exception.parse_error.101] " prefix and cuts the
// input it quotes ("last read: '...'", "number overflow parsing '...'").
std::string WithoutExceptionId(const std::string& message) {
  std::string text = message;
  if (!text.empty() && text.front() == '[') {
    const size_t end = text.find("] ");
    if (end != std::string::npos) text = text.substr(end + 2);
  }
  for (const char* marker : {"last read: '", "parsing '"}) {
    const size_t start = text.find(marker);
    const size_t end = text.rfind('\'');
    if (start == std::string::npos) continue;
    const size_t from = start + std::strlen(marker);
    if (end == std::string::npos || end < from) continue;
    text = text.substr(0, from) + ClipInput(text.substr(from, end - from)) + text.substr(end);
  }
  return ClipInput(text, 4 * kMaxEchoedInput);
}

// Follows the key path while nlohmann parses, so that parse errors can say
// where they happened, and rejects duplicate keys in an object (nlohmann would
// silently keep the last one).
class KeyPathTracker {
 public:
  explicit KeyPathTracker(const std::string& source) : source_(source) {}

  // The nlohmann parser callback.
  bool OnEvent(json::parse_event_t event, const json& parsed) {
    switch (event) {
      case json::parse_event_t::object_start:
        frames_.push_back(Frame{false, {}, 0, {}});
        break;
      case json::parse_event_t::array_start:
        frames_.push_back(Frame{true, {}, 0, {}});
        break;
      case json::parse_event_t::key: {
        Frame& frame = frames_.back();
        frame.key = parsed.get<std::string>();
        if (!frame.keys.insert(frame.key).second) {
          throw InputError(source_, CurrentPath(), "duplicate key in the same object");
        }
        break;
      }
      case json::parse_event_t::object_end:
      case json::parse_event_t::array_end:
        frames_.pop_back();
        [[fallthrough]];
      case json::parse_event_t::value:
        if (!frames_.empty() && frames_.back().is_array) ++frames_.back().index;
        break;
    }
    return true;
  }

  // Key path of the value being read, e.g. "springs[2].stiffness".
  std::string CurrentPath() const {
    std::string path;
    for (const Frame& frame : frames_) {
      if (frame.is_array) {
        path += "[" + std::to_string(frame.index) + "]";
      } else {
        path += (path.empty() ? "" : ".") + frame.key;
      }
    }
    return path;
  }

 private:
  struct Frame {
    bool is_array;
    std::string key;  // current key (objects)
    size_t index;     // current element (arrays)
    std::set<std::string> keys;
  };

  const std::string& source_;
  std::vector<Frame> frames_;
};

// Reads a scene file: a regular file (not a directory, device or pipe such as
// /dev/zero, which never ends) of at most kMaxSceneFileBytes.
std::string ReadTextFile(const std::string& path) {
  namespace fs = std::filesystem;
  const std::string problem = InputFileProblem(path);
  if (!problem.empty()) throw InputError(path + ": cannot read scene file: " + problem);
  std::error_code error;
  const fs::file_status status = fs::status(path, error);
  const std::string too_large = path + ": cannot read scene file: larger than the limit of " +
                                std::to_string(kMaxSceneFileBytes >> 20) + " MiB";
  if (fs::exists(status) && fs::file_size(path, error) > kMaxSceneFileBytes && !error) {
    throw InputError(too_large);
  }
  std::ifstream file(path, std::ios::binary);
  if (!file) {
    throw InputError(path + ": cannot open scene file: " + std::strerror(errno));
  }
  // Read with the limit as well: the file may grow, or report no size (procfs).
  std::string text;
  std::vector<char> buffer(1 << 16);
  while (file.read(buffer.data(), static_cast<std::streamsize>(buffer.size())) ||
         file.gcount() > 0) {
    text.append(buffer.data(), static_cast<size_t>(file.gcount()));
    if (text.size() > kMaxSceneFileBytes) throw InputError(too_large);
  }
  if (file.bad()) throw InputError(path + ": cannot read scene file: " + std::strerror(errno));
  return text;
}

std::string BuiltinSource(const std::string& name) { return "problems/" + name + ".json"; }

std::string BuiltinNameList() {
  const std::set<std::string> names = BuiltinSceneNames();
  return internal::Join(std::vector<std::string>(names.begin(), names.end()));
}

}  // namespace

Scene ParseScene(const std::string& text, const std::string& source,
                 const SceneLoadOptions& options) {
  // nlohmann stops at a NUL byte as at the end of the input, which would
  // accept a valid scene followed by anything; JSON text never contains one.
  const size_t nul = text.find('\0');
  if (nul != std::string::npos) {
    throw InputError(source + ": malformed JSON: NUL byte at offset " + std::to_string(nul) +
                     " (a JSON text cannot contain one)");
  }
  KeyPathTracker tracker(source);
  json document;
  try {
    document = json::parse(text, [&tracker](int, json::parse_event_t event, json& parsed) {
      return tracker.OnEvent(event, parsed);
    });
  } catch (const json::parse_error& error) {
    const std::string path = tracker.CurrentPath();
    throw InputError(source + ": malformed JSON" +
                     (path.empty() ? "" : " (near " + ClipInput(path) + ")") + ": " +
                     WithoutExceptionId(error.what()));
  } catch (const json::out_of_range& error) {
    // A number such as 1e400, read as the value at CurrentPath().
    throw InputError(source, tracker.CurrentPath(),
                     "number out of the range of a double: " + WithoutExceptionId(error.what()));
  } catch (const json::exception& error) {
    throw InputError(source + ": malformed JSON: " + WithoutExceptionId(error.what()));
  }
  return ParseScene(document, source, options);
}

Scene ParseScene(const nlohmann::json& document, const std::string& source,
                 const SceneLoadOptions& options) {
  try {
    return internal::SceneParser(source, options).Parse(document);
  } catch (const nlohmann::json::exception& error) {
    // Not expected (every access is checked first); keeps the promise that bad
    // input only ever raises InputError.
    throw InputError(source + ": " + WithoutExceptionId(error.what()));
  }
}

Scene LoadSceneFile(const std::string& path, const SceneLoadOptions& options) {
  return ParseScene(ReadTextFile(path), path, options);
}

std::set<std::string> BuiltinSceneNames() {
  std::set<std::string> names;
  for (const auto& entry : internal::BuiltinSceneTexts()) names.insert(entry.first);
  return names;
}

bool IsBuiltinScene(const std::string& name) {
  return internal::BuiltinSceneTexts().count(name) != 0;
}

std::string BuiltinSceneText(const std::string& name) {
  const auto& texts = internal::BuiltinSceneTexts();
  const auto found = texts.find(name);
  if (found == texts.end()) {
    throw InputError(ClipInput(name) +
                     ": unknown built-in scene (built-in scenes: " + BuiltinNameList() + ")");
  }
  return found->second;
}

Scene LoadScene(const std::string& name_or_path, const SceneLoadOptions& options) {
  if (name_or_path.empty()) {
    throw InputError("scene: the name is empty: give a built-in scene (" + BuiltinNameList() +
                     ") or a JSON file");
  }
  if (IsBuiltinScene(name_or_path)) {
    return ParseScene(BuiltinSceneText(name_or_path), BuiltinSource(name_or_path), options);
  }
  std::error_code error;
  if (std::filesystem::exists(name_or_path, error)) return LoadSceneFile(name_or_path, options);
  throw InputError(ClipInput(name_or_path) +
                   ": no such scene file, and not a built-in scene (built-in scenes: " +
                   BuiltinNameList() + ")");
}

}  // namespace ipstep
