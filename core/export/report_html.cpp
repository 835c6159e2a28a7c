#include "export/report_html.h"

#include <sstream>

#include "common/atomic_file.h"

namespace storey {

std::string htmlEscape(const std::string& s) {
  std::string out;
  for (char c : s) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

namespace {

/// Inline markup: `code`, **bold**, ![alt](src); the rest escaped.
std::string inlineHtml(const std::string& s) {
  std::string out;
  std::size_t i = 0;
  while (i < s.size()) {
    if (s[i] == '`') {
      const std::size_t end = s.find('`', i + 1);
      if (end != std::string::npos) {
        out += "<code>" + htmlEscape(s.substr(i + 1, end - i - 1)) + "</code>";
        i = end + 1;
        continue;
      }
    }
    if (s.compare(i, 2, "**") == 0) {
      const std::size_t end = s.find("**", i + 2);
      if (end != std::string::npos) {
        out += "<strong>" + inlineHtml(s.substr(i + 2, end - i - 2)) + "</strong>";
        i = end + 2;
        continue;
      }
    }
    if (s.compare(i, 2, "![") == 0) {
      const std::size_t close = s.find("](", i + 2);
      const std::size_t end = close == std::string::npos ? close : s.find(')', close + 2);
      if (end != std::string::npos) {
        const std::string alt = s.substr(i + 2, close - i - 2);
        const std::string src = s.substr(close + 2, end - close - 2);
        out += "<a href=\"" + htmlEscape(src) + "\"><img src=\"" + htmlEscape(src) + "\" alt=\"" +
               htmlEscape(alt) + "\"></a>";
        i = end + 1;
        continue;
      }
    }
    out += htmlEscape(std::string(1, s[i]));
    ++i;
  }
  return out;
}

std::vector<std::string> tableCells(const std::string& line) {
  std::vector<std::string> cells;
  std::string t = line;
  if (!t.empty() && t.front() == '|') t.erase(0, 1);
  if (!t.empty() && t.back() == '|') t.pop_back();
  std::stringstream ss(t);
  std::string cell;
  while (std::getline(ss, cell, '|')) {
    const auto a = cell.find_first_not_of(' ');
    const auto b = cell.find_last_not_of(' ');
    cells.push_back(a == std::string::npos ? "" : cell.substr(a, b - a + 1));
  }
  return cells;
}

constexpr const char* kStyle = R"(
body { font-family: -apple-system, "Segoe UI", Helvetica, Arial, sans-serif; max-width: 1100px;
       margin: 2em auto; padding: 0 1em; color: #222; line-height: 1.45; }
h1 { border-bottom: 2px solid #ddd; padding-bottom: .3em; }
h2 { border-bottom: 1px solid #eee; padding-bottom: .2em; margin-top: 1.8em; }
table { border-collapse: collapse; margin: 1em 0; font-size: 0.92em; }
th, td { border: 1px solid #ccc; padding: .3em .6em; }
th { background: #f3f3f3; }
td.r, th.r { text-align: right; font-variant-numeric: tabular-nums; }
code { background: #f4f4f4; padding: 0 .25em; border-radius: 3px; }
img { max-width: 100%; border: 1px solid #ddd; }
)";

}  // namespace

const char* reportHtmlStyle() {
  return kStyle;
}

std::string markdownToHtml(const std::string& markdown) {
  std::ostringstream html;
  std::istringstream in(markdown);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  std::string paragraph;
  auto flush = [&]() {
    if (!paragraph.empty()) html << "<p>" << paragraph << "</p>\n";
    paragraph.clear();
  };
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const std::string& line = lines[i];
    if (line.empty()) {
      flush();
      continue;
    }
    if (line[0] == '#') {
      flush();
      std::size_t level = line.find_first_not_of('#');
      const std::string text =
          level == std::string::npos ? "" : line.substr(level + (line[level] == ' ' ? 1 : 0));
      level = std::min<std::size_t>(level == std::string::npos ? line.size() : level, 6);
      html << "<h" << level << ">" << inlineHtml(text) << "</h" << level << ">\n";
      continue;
    }
    if (line[0] == '|' && i + 1 < lines.size() && lines[i + 1].rfind("|-", 0) == 0) {
      flush();
      const std::vector<std::string> header = tableCells(line);
      const std::vector<std::string> align = tableCells(lines[i + 1]);
      auto cls = [&](std::size_t k) {
        return k < align.size() && !align[k].empty() && align[k].back() == ':' ? " class=\"r\""
                                                                               : "";
      };
      html << "<table>\n<tr>";
      for (std::size_t k = 0; k < header.size(); ++k)
        html << "<th" << cls(k) << ">" << inlineHtml(header[k]) << "</th>";
      html << "</tr>\n";
      i += 2;
      for (; i < lines.size() && !lines[i].empty() && lines[i][0] == '|'; ++i) {
        const std::vector<std::string> cells = tableCells(lines[i]);
        html << "<tr>";
        for (std::size_t k = 0; k < cells.size(); ++k)
          html << "<td" << cls(k) << ">" << inlineHtml(cells[k]) << "</td>";
        html << "</tr>\n";
      }
      html << "</table>\n";
      --i;
      continue;
    }
    if (line.rfind("- ", 0) == 0) {
      flush();
      html << "<ul>\n";
      for (; i < lines.size() && lines[i].rfind("- ", 0) == 0; ++i)
        html << "<li>" << inlineHtml(lines[i].substr(2)) << "</li>\n";
      html << "</ul>\n";
      --i;
      continue;
    }
    const bool hard_break = line.size() >= 2 && line.compare(line.size() - 2, 2, "  ") == 0;
    if (!paragraph.empty()) paragraph += "\n";
    paragraph += inlineHtml(hard_break ? line.substr(0, line.size() - 2) : line);
    if (hard_break) paragraph += "<br>";
  }
  flush();
  return html.str();
}

std::string reportHtml(const std::string& report_json, const std::vector<ReportImage>& images) {
  const std::string body = markdownToHtml(reportMarkdown(report_json, images));
  std::ostringstream html;
  html << "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
          "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n"
          "<title>Storey run report</title>\n<style>"
       << kStyle << "</style>\n</head>\n<body>\n"
       << body << "</body>\n</html>\n";
  return html.str();
}

void writeReportHtml(const std::string& report_json, const std::string& path,
                     const std::vector<ReportImage>& images) {
  writeFileAtomically(path, reportHtml(report_json, images));
}

}  // namespace storey
