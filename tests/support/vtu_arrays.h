// Test-only reader of the DataArrays of a .vtu as io/vtk_unstructured_grid.h
// writes them: inline ASCII, or binary appended data (raw: a UInt64 byte
// count before each array; zlib: VTK's block header, then the blocks), so
// that the tests check the bytes a reader sees, not the writer's own view.
#pragma once

#include <zlib.h>

#include <cstdint>
#include <cstring>
#include <map>
#include <regex>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace ipstep::testing {

class VtuArrays {
 public:
  explicit VtuArrays(const std::string& vtu) {
    const size_t appended = vtu.find("<AppendedData");
    xml_ = vtu.substr(0, appended);
    if (appended != std::string::npos) data_ = vtu.substr(vtu.find('_', appended) + 1);
    zlib_ = xml_.find("compressor=\"vtkZLibDataCompressor\"") != std::string::npos;
  }

  // The values of the DataArray named `name` ("" for the Points); empty if
  // there is none.
  std::vector<double> Values(const std::string& name) const {
    const std::regex array("<DataArray type=\"(\\w+)\"" +
                           (name.empty() ? std::string("(?! Name)") : " Name=\"" + name + "\"") +
                           "[^>]*format=\"(\\w+)\"(?: offset=\"(\\d+)\")?");
    std::smatch m;
    if (!std::regex_search(xml_, m, array)) return {};
    const std::string type = m[1];
    if (m[2] == "ascii") {
      const size_t start = m.position(0) + xml_.substr(m.position(0)).find('>') + 1;
      std::stringstream in(xml_.substr(start, xml_.find("</DataArray>", start) - start));
      std::vector<double> values;
      for (double v; in >> v;) values.push_back(v);
      return values;
    }
    return Decode(type, Bytes(std::stoul(m[3])));
  }

  // The bytes of the appended array at `offset` (decompressed).
  std::string Bytes(size_t offset) const {
    if (!zlib_) return data_.substr(offset + 8, Header(offset));
    const std::uint64_t blocks = Header(offset), block_size = Header(offset + 8),
                        last = Header(offset + 16);
    std::string bytes;
    size_t at = offset + 24 + 8 * blocks;
    for (std::uint64_t b = 0; b < blocks; ++b) {
      const std::uint64_t length = Header(offset + 24 + 8 * b);
      uLongf size = b + 1 == blocks && last != 0 ? last : block_size;
      std::string block(size, '\0');
      if (uncompress(reinterpret_cast<Bytef*>(block.data()), &size,
                     reinterpret_cast<const Bytef*>(data_.data() + at), length) != Z_OK) {
        throw std::runtime_error("a zlib block does not decompress");
      }
      bytes += block.substr(0, size);
      at += length;
    }
    return bytes;
  }

  // The UInt64 at `offset` of the appended data (a header entry).
  std::uint64_t Header(size_t offset) const {
    std::uint64_t value;
    std::memcpy(&value, data_.data() + offset, 8);
    return value;
  }

 private:
  template <typename T>
  static std::vector<double> As(const std::string& bytes) {
    std::vector<double> values(bytes.size() / sizeof(T));
    for (size_t i = 0; i < values.size(); ++i) {
      T v;
      std::memcpy(&v, bytes.data() + i * sizeof(T), sizeof(T));
      values[i] = static_cast<double>(v);
    }
    return values;
  }
  static std::vector<double> Decode(const std::string& type, const std::string& bytes) {
    if (type == "Float64") return As<double>(bytes);
    if (type == "Float32") return As<float>(bytes);
    if (type == "Int32") return As<std::int32_t>(bytes);
    if (type == "UInt8") return As<std::uint8_t>(bytes);
    throw std::runtime_error("unexpected DataArray type " + type);
  }

  std::string xml_, data_;
  bool zlib_ = false;
};

}  // namespace ipstep::testing
