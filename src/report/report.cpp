// The page: each top-level group of the file goes to the panel file that reads it
// (<kind>_panels.cpp, shared readers in panel_common.cpp); this file assembles their JSON and
// fills the embedded template with it.
#include "report/report.hpp"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "common/embedded.hpp"
#include "common/error.hpp"
#include "io/h5_file.hpp"
#include "io/output_lock.hpp"
#include "io/output_path.hpp"
#include "report/panel_common.hpp"
#include "report/panels.hpp"

namespace phasmid::report {
namespace {

using nlohmann::json;
using io::H5Reader;

std::string root_attr(const H5Reader& r, const std::string& name) {
  try {
    return r.read_string_attribute("/", name);
  } catch (const Error&) {
    return "";
  }
}

std::string read_embedded(const std::string& key) {
  const auto& files = embedded::files();
  auto it = files.find(key);
  if (it == files.end()) throw Error("report asset " + key + " is not embedded in this build");
  return it->second;
}

// A file of a verb whose result group is missing did not finish (e.g. a gsa file of an older
// phasmid killed during its analysis, which left /sweep alone): refused, not drawn as if whole.
void refuse_unfinished(const H5Reader& r, const std::string& h5_path) {
  static const std::map<std::string, std::string> result_of = {{"gsa", "/gsa"}, {"continue", "/continuation"}, {"fit", "/fit"}};
  std::istringstream words(root_attr(r, "command"));
  std::string program, verb;
  words >> program >> verb;
  const auto it = result_of.find(verb);
  if (it == result_of.end() || r.exists(it->second)) return;
  throw Error(h5_path + ": a `phasmid " + verb + "` file without " + it->second + ": the run ended before its result was " +
              "written" + (verb == "gsa" ? "; `phasmid gsa CONFIG -o " + h5_path + " --resume` analyses it" : ""));
}

}  // namespace

std::string json_for_script(const nlohmann::json& j) {
  std::string s = j.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
  std::string out;
  out.reserve(s.size() + s.size() / 50);
  for (char c : s) {
    if (c == '<')
      out += "\\u003c";
    else
      out += c;
  }
  return out;
}

nlohmann::json extract(const std::string& h5_path, std::size_t max_points) {
  H5Reader r(h5_path);  // throws phasmid::Error: no such file / not an HDF5 file
  refuse_unfinished(r, h5_path);
  json out = json::object();
  out["source"] = std::filesystem::path(h5_path).filename().string();
  out["attrs"] = {{"phasmid_version", root_attr(r, "phasmid_version")},
                  {"command", root_attr(r, "command")},
                  {"created", root_attr(r, "created")},
                  {"config", root_attr(r, "config")}};
  out["ignored"] = json::array();
  out["max_points"] = max_points;
  for (const auto& top : r.children("/")) {
    const std::string p = "/" + top;
    if (!r.is_group(p)) {
      note_ignored(out, p);
      continue;
    }
    // A group this report cannot read (unexpected types or shapes) is listed, not fatal.
    try {
      if (top == "trajectory")
        extract_trajectory(r, out, max_points);
      else if (top == "parameters")
        extract_parameters(r, out);
      else if (top == "features")
        extract_features(r, out);
      else if (top == "sensitivity")
        extract_sensitivity(r, out);
      else if (top == "fit")
        extract_fit(r, out, max_points);
      else if (top == "sweep")
        extract_sweep(r, out);
      else if (top == "gsa")
        out["gsa"] = extract_gsa(r);
      else if (top == "continuation")
        extract_continuation(r, out);
      else
        note_ignored(out, p);
    } catch (const Error& e) {
      out.erase(top);
      note_ignored(out, p + " (unreadable: " + e.what() + ")");
    }
  }
  return out;
}

std::string render_html(const nlohmann::json& data) {
  std::string tpl = read_embedded("reports/report.html");
  const std::vector<std::pair<std::string, std::string>> parts = {
      {"/*PHASMID_CSS*/", read_embedded("reports/report.css")},
      {"/*PHASMID_VENDOR_JS*/",
       read_embedded("reports/vendor/chart.umd.min.js") + "\n" +
           read_embedded("reports/vendor/chartjs-chart-matrix.min.js")},
      {"/*PHASMID_REPORT_JS*/", read_embedded("reports/report.js")},
      {"/*PHASMID_DATA*/", json_for_script(data)},
      {"PHASMID_TITLE", [&] {
         std::string s = "phasmid report: " + data.value("source", std::string());
         std::string e;
         for (char c : s) {
           if (c == '<') e += "&lt;";
           else if (c == '>') e += "&gt;";
           else if (c == '&') e += "&amp;";
           else e += c;
         }
         return e;
       }()}};
  // One pass over the template: inserted text is never scanned for markers again.
  std::string out;
  std::size_t pos = 0;
  while (true) {
    std::size_t best = std::string::npos;
    const std::pair<std::string, std::string>* which = nullptr;
    for (const auto& p : parts) {
      auto f = tpl.find(p.first, pos);
      if (f < best) best = f, which = &p;
    }
    if (!which) break;
    out.append(tpl, pos, best - pos);
    out += which->second;
    pos = best + which->first.size();
  }
  out.append(tpl, pos, std::string::npos);
  return out;
}

std::string default_output_path(const std::string& h5_path) {
  std::filesystem::path p(h5_path);
  p.replace_extension(".html");
  return p.string();
}

void write_report(const std::string& h5_path, const std::string& html_path) {
  io::check_output_path(html_path, {h5_path});
  const std::string html = render_html(extract(h5_path));  // reads only the input: its errors first
  io::HeldOutputLock lock(html_path);  // before "<html>.tmp" (the locked file) is written; makes the directory
  const std::string tmp = lock.get().tmp_path();
  {
    std::ofstream f(tmp, std::ios::binary | std::ios::trunc);
    if (!f) throw Error("cannot write " + tmp);
    f.write(html.data(), static_cast<std::streamsize>(html.size()));
    f.close();
    if (!f) {
      std::remove(tmp.c_str());
      throw Error("cannot write " + tmp);
    }
  }
  std::error_code ec;
  std::filesystem::rename(tmp, html_path, ec);
  if (ec) {
    std::remove(tmp.c_str());
    throw Error("cannot rename " + tmp + " to " + html_path + ": " + ec.message());
  }
}

}  // namespace phasmid::report
