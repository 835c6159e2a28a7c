#pragma once
/// report.html: the same report as report.md (reportMarkdown), as one HTML
/// page with its style inline; the images are the PNGs next to it
/// (renders/*.png), referenced by relative paths. Opens in any browser.
#include <string>
#include <vector>

#include "export/report_markdown.h"

namespace storey {

/// Throws storey::Error when `report_json` is not a JSON object.
std::string reportHtml(const std::string& report_json, const std::vector<ReportImage>& images = {});
/// Writes reportHtml(report_json, images) atomically to `path`.
void writeReportHtml(const std::string& report_json, const std::string& path,
                     const std::vector<ReportImage>& images = {});
/// The Markdown subset reportMarkdown writes (headings, paragraphs, `code`,
/// **bold**, trailing-two-space line breaks, pipe tables with an alignment
/// row, "- " lists, ![alt](src) images) as HTML body content. Text is escaped.
std::string markdownToHtml(const std::string& markdown);
/// `s` with & < > " escaped for HTML text and attribute values.
std::string htmlEscape(const std::string& s);
/// The report pages' inline CSS (also used by the fleet report of `storey batch`).
const char* reportHtmlStyle();

}  // namespace storey
