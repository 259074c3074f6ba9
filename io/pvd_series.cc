#include "io/pvd_series.h"

#include <charconv>

namespace ipstep {
namespace {

std::string XmlAttribute(const std::string& text) {
  std::string escaped;
  for (char c : text) {
    if (c == '&') {
      escaped += "&amp;";
    } else if (c == '"') {
      escaped += "&quot;";
    } else if (c == '<') {
      escaped += "&lt;";
    } else {
      escaped += c;
    }
  }
  return escaped;
}

}  // namespace

PvdSeries::PvdSeries(const std::string& path, const std::string& output)
    : file_(path, "output: " + output, std::ios::binary | std::ios::trunc) {
  std::ostream& out = file_.stream();
  out << "<?xml version=\"1.0\"?>\n"
         "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
         "<Collection>\n";
  end_of_entries_ = out.tellp();
  WriteClosingTags();
}

void PvdSeries::Add(double time, int part, const std::string& name, const std::string& file) {
  std::ostream& out = file_.stream();
  out.seekp(end_of_entries_);
  char digits[32];  // the shortest text that reads back as `time`
  const auto printed = std::to_chars(digits, digits + sizeof(digits), time);
  out << "<DataSet timestep=\"" << std::string(digits, printed.ptr) << "\" group=\"\" part=\""
      << part << "\" name=\"" << XmlAttribute(name) << "\" file=\"" << XmlAttribute(file)
      << "\"/>\n";
  end_of_entries_ = out.tellp();
  WriteClosingTags();
}

void PvdSeries::WriteClosingTags() {
  file_.stream() << "</Collection>\n</VTKFile>\n";
  file_.Flush();
}

}  // namespace ipstep
