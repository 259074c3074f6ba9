#include "io/pvd_series.h"

#include <iomanip>

#include "core/input_error.h"

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
    : path_(path), output_(output), out_(path, std::ios::binary | std::ios::trunc) {
  if (!out_) throw InputError("output", output_, "cannot write '" + path_ + "'");
  out_ << std::setprecision(15)
       << "<?xml version=\"1.0\"?>\n"
          "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
          "<Collection>\n";
  end_of_entries_ = out_.tellp();
  WriteClosingTags();
}

void PvdSeries::Add(double time, int part, const std::string& file) {
  out_.seekp(end_of_entries_);
  out_ << "<DataSet timestep=\"" << time << "\" group=\"\" part=\"" << part << "\" file=\""
       << XmlAttribute(file) << "\"/>\n";
  end_of_entries_ = out_.tellp();
  WriteClosingTags();
}

void PvdSeries::WriteClosingTags() {
  out_ << "</Collection>\n</VTKFile>\n" << std::flush;
  if (!out_) throw InputError("output", output_, "cannot write '" + path_ + "'");
}

}  // namespace ipstep
