#include "io/vtk_unstructured_grid.h"

#include <zlib.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstring>
#include <limits>
#include <type_traits>

#include "io/output_file.h"

namespace ipstep {

const char* VtkEncodingName(VtkEncoding encoding) {
  switch (encoding) {
    case VtkEncoding::kAscii:
      return "ascii";
    case VtkEncoding::kRaw:
      return "raw";
    case VtkEncoding::kZlib:
      return "zlib";
  }
  return "?";
}

bool ParseVtkEncoding(const std::string& name, VtkEncoding* encoding) {
  for (VtkEncoding e : {VtkEncoding::kAscii, VtkEncoding::kRaw, VtkEncoding::kZlib}) {
    if (name == VtkEncodingName(e)) {
      *encoding = e;
      return true;
    }
  }
  return false;
}

const char* VtkPrecisionName(VtkPrecision precision) {
  return precision == VtkPrecision::kFloat32 ? "float32" : "float64";
}

bool ParseVtkPrecision(const std::string& name, VtkPrecision* precision) {
  for (VtkPrecision p : {VtkPrecision::kFloat32, VtkPrecision::kFloat64}) {
    if (name == VtkPrecisionName(p)) {
      *precision = p;
      return true;
    }
  }
  return false;
}

void VtkMesh::AddCell(VtkCell type, std::vector<int> cell_points) {
  cells.push_back(std::move(cell_points));
  types.push_back(type);
}

namespace {

static_assert(sizeof(double) == 8 && sizeof(float) == 4 && sizeof(std::int32_t) == 4);

double Finite(double value) { return std::isfinite(value) ? value : 0.0; }

bool LittleEndian() {
  const std::uint16_t one = 1;
  unsigned char first;
  std::memcpy(&first, &one, 1);
  return first == 1;
}

// The bytes of `values`, little-endian.
template <typename T>
std::string Bytes(const std::vector<T>& values) {
  std::string bytes(values.size() * sizeof(T), '\0');
  if (!bytes.empty()) std::memcpy(bytes.data(), values.data(), bytes.size());
  if (!LittleEndian()) {
    for (size_t at = 0; at < bytes.size(); at += sizeof(T)) {
      for (size_t k = 0; k < sizeof(T) / 2; ++k)
        std::swap(bytes[at + k], bytes[at + sizeof(T) - 1 - k]);
    }
  }
  return bytes;
}

void AppendUInt64(std::uint64_t value, std::string* out) {
  *out += Bytes(std::vector<std::uint64_t>{value});
}

constexpr std::uint64_t kBlockSize = 32768;  // VTK's default compressor block

// VTK's compressed layout (the header comment); false if zlib fails (out of
// memory: compressBound leaves room for any input).
bool Compressed(const std::string& bytes, std::string* out) {
  const std::uint64_t size = bytes.size();
  const std::uint64_t blocks = (size + kBlockSize - 1) / kBlockSize;
  std::vector<std::uint64_t> header{blocks, kBlockSize, size % kBlockSize};
  std::string data;
  for (std::uint64_t b = 0; b < blocks; ++b) {
    const std::uint64_t length = std::min(kBlockSize, size - b * kBlockSize);
    std::string block(compressBound(length), '\0');
    uLongf written = block.size();
    if (compress2(reinterpret_cast<Bytef*>(block.data()), &written,
                  reinterpret_cast<const Bytef*>(bytes.data() + b * kBlockSize), length,
                  Z_BEST_SPEED) != Z_OK) {
      return false;
    }
    header.push_back(written);
    data.append(block, 0, written);
  }
  *out += Bytes(header) + data;
  return true;
}

template <typename T>
void AppendNumber(T value, std::string* text) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof(buffer), value);
  text->append(buffer, result.ptr);
}

void AppendNumber(long long value, std::string* text) { *text += std::to_string(value); }

// One <DataArray>: inline text (kAscii) or an offset into the appended data.
class ArrayWriter {
 public:
  ArrayWriter(std::ostream& xml, VtkEncoding encoding, VtkPrecision precision)
      : xml_(xml), encoding_(encoding), precision_(precision) {}

  // Finite floating-point values as Float32 or Float64 (the precision).
  void WriteReals(const std::string& name, int components, const std::vector<double>& values) {
    if (precision_ == VtkPrecision::kFloat64) {
      Write("Float64", name, components, values);
    } else {
      std::vector<float> floats;
      floats.reserve(values.size());
      for (double v : values) {
        // Beyond float's range is written as 0, as a non-finite number.
        floats.push_back(std::abs(v) <= std::numeric_limits<float>::max() ? static_cast<float>(v)
                                                                          : 0.0f);
      }
      Write("Float32", name, components, floats);
    }
  }

  template <typename T>
  void Write(const char* type, const std::string& name, int components,
             const std::vector<T>& values) {
    xml_ << "<DataArray type=\"" << type << "\"";
    if (!name.empty()) xml_ << " Name=\"" << name << "\"";
    if (components > 1) xml_ << " NumberOfComponents=\"" << components << "\"";
    if (encoding_ == VtkEncoding::kAscii) {
      std::string text;
      for (size_t i = 0; i < values.size(); ++i) {
        if constexpr (std::is_floating_point_v<T>) {
          AppendNumber(values[i], &text);
        } else {
          AppendNumber(static_cast<long long>(values[i]), &text);
        }
        text += (i + 1) % components == 0 ? '\n' : ' ';
      }
      xml_ << " format=\"ascii\">\n" << text << "</DataArray>\n";
      return;
    }
    xml_ << " format=\"appended\" offset=\"" << appended_.size() << "\"/>\n";
    const std::string bytes = Bytes(values);
    if (encoding_ == VtkEncoding::kZlib) {
      compressed_ = Compressed(bytes, &appended_) && compressed_;
    } else {
      AppendUInt64(bytes.size(), &appended_);
      appended_ += bytes;
    }
  }

  const std::string& appended() const { return appended_; }
  // False if zlib failed on an array.
  bool compressed() const { return compressed_; }

 private:
  std::ostream& xml_;
  VtkEncoding encoding_;
  VtkPrecision precision_;
  std::string appended_;
  bool compressed_ = true;
};

std::vector<double> Flat(const std::vector<Eigen::Vector3d>& vectors) {
  std::vector<double> flat;
  flat.reserve(3 * vectors.size());
  for (const Eigen::Vector3d& v : vectors) {
    for (int k = 0; k < 3; ++k) flat.push_back(Finite(v[k]));
  }
  return flat;
}

std::vector<double> Finites(std::vector<double> values) {
  for (double& v : values) v = Finite(v);
  return values;
}

}  // namespace

void WriteVtu(const VtkMesh& mesh, const std::string& path, const std::string& output,
              VtkEncoding encoding, VtkPrecision precision) {
  OutputFile file(path, "output: " + output, std::ios::binary | std::ios::trunc);
  std::ostream& out = file.stream();
  out << "<?xml version=\"1.0\"?>\n"
         "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" "
         "header_type=\"UInt64\""
      << (encoding == VtkEncoding::kZlib ? " compressor=\"vtkZLibDataCompressor\"" : "")
      << ">\n<UnstructuredGrid>\n<Piece NumberOfPoints=\"" << mesh.points.size()
      << "\" NumberOfCells=\"" << mesh.cells.size() << "\">\n";
  ArrayWriter arrays(out, encoding, precision);
  out << "<PointData>\n";
  for (const auto& [name, values] : mesh.point_vectors) {
    arrays.WriteReals(name, 3, Flat(values));
  }
  out << "</PointData>\n<CellData>\n";
  for (const auto& [name, values] : mesh.cell_integers) {
    arrays.Write("Int32", name, 1, std::vector<std::int32_t>(values.begin(), values.end()));
  }
  for (const auto& [name, values] : mesh.cell_scalars) {
    arrays.WriteReals(name, 1, Finites(values));
  }
  out << "</CellData>\n<Points>\n";
  arrays.WriteReals("", 3, Flat(mesh.points));
  out << "</Points>\n<Cells>\n";
  std::vector<std::int32_t> connectivity, offsets;
  for (const std::vector<int>& cell : mesh.cells) {
    connectivity.insert(connectivity.end(), cell.begin(), cell.end());
    offsets.push_back(static_cast<std::int32_t>(connectivity.size()));
  }
  std::vector<std::uint8_t> types;
  for (VtkCell type : mesh.types) types.push_back(static_cast<std::uint8_t>(type));
  arrays.Write("Int32", "connectivity", 1, connectivity);
  arrays.Write("Int32", "offsets", 1, offsets);
  arrays.Write("UInt8", "types", 1, types);
  out << "</Cells>\n</Piece>\n</UnstructuredGrid>\n";
  if (!arrays.compressed()) {
    throw OutputError(file.label(), path, OutputError::Kind::kWrite, "zlib could not compress");
  }
  if (encoding != VtkEncoding::kAscii) {
    out << "<AppendedData encoding=\"raw\">\n_";
    out.write(arrays.appended().data(), static_cast<std::streamsize>(arrays.appended().size()));
    out << "\n</AppendedData>\n";
  }
  out << "</VTKFile>\n";
  file.Close();
}

}  // namespace ipstep
