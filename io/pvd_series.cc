#include "io/pvd_series.h"

#include <cstdio>
#include <fstream>
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

PvdSeries::PvdSeries(std::string path, std::string flag)
    : path_(std::move(path)), flag_(std::move(flag)) {}

void PvdSeries::Add(double time, int part, const std::string& file) {
  entries_.push_back({time, part, file});
  const std::string temporary = path_ + ".part";
  {
    std::ofstream out(temporary);
    if (!out) throw InputError("flag", flag_, "cannot write '" + temporary + "'");
    out << std::setprecision(15)
        << "<?xml version=\"1.0\"?>\n"
           "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
           "<Collection>\n";
    for (const Entry& e : entries_) {
      out << "<DataSet timestep=\"" << e.time << "\" group=\"\" part=\"" << e.part << "\" file=\""
          << XmlAttribute(e.file) << "\"/>\n";
    }
    out << "</Collection>\n</VTKFile>\n";
    if (!out) throw InputError("flag", flag_, "cannot write '" + temporary + "'");
  }
  if (std::rename(temporary.c_str(), path_.c_str()) != 0) {
    throw InputError("flag", flag_, "cannot write '" + path_ + "'");
  }
}

}  // namespace ipstep
