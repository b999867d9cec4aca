// The report of an experiment: Markdown and HTML from the same blocks, CSV tables, SVG plots
// drawn here (a plotting library would be a dependency for a few lines and points), PNG images,
// results.json; all written into the folder atomically.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <sstream>

#include "core/atomic_file.hpp"
#include "experiments/experiment_support.hpp"
#include "lfcam/io/image_io.hpp"

namespace lfcam::experiments {

std::string fixed(double value, int decimals) {
  if (!std::isfinite(value)) return "n/a";
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*f", decimals, value);
  return buffer;
}

namespace {

std::string escapeXml(const std::string& text) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

// Round numbers for axis ticks: 1, 2 or 5 times a power of ten.
std::vector<double> ticks(double lo, double hi) {
  const double span = hi - lo;
  if (!(span > 0)) return {lo};
  const double raw = span / 5, power = std::pow(10, std::floor(std::log10(raw)));
  const double step = raw / power < 1.5   ? power
                      : raw / power < 3.5 ? 2 * power
                      : raw / power < 7.5 ? 5 * power
                                          : 10 * power;
  std::vector<double> out;
  for (double t = std::ceil(lo / step) * step; t <= hi + 1e-9 * span; t += step)
    out.push_back(std::abs(t) < 1e-12 * step ? 0 : t);
  return out;
}

std::string tickLabel(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%g", value);
  return buffer;
}

const char* colour(std::size_t i) {
  static const char* palette[] = {"#1f77b4", "#d62728", "#2ca02c", "#ff7f0e", "#9467bd", "#8c564b", "#17becf"};
  return palette[i % 7];
}

}  // namespace

std::string plotSvg(const Plot& plot) {
  const double width = 640, height = 400, left = 70, right = 170, top = 40, bottom = 55;
  const double plotW = width - left - right, plotH = height - top - bottom;
  auto tx = [&](double x) { return plot.logX ? std::log10(x) : x; };
  double x0 = std::numeric_limits<double>::infinity(), x1 = -x0, y0 = x0, y1 = -x0;
  for (const auto& s : plot.series)
    for (std::size_t i = 0; i < s.x.size(); ++i) {
      if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i]) || (plot.logX && !(s.x[i] > 0))) continue;
      x0 = std::min(x0, tx(s.x[i])), x1 = std::max(x1, tx(s.x[i]));
      y0 = std::min(y0, s.y[i]), y1 = std::max(y1, s.y[i]);
    }
  for (const auto& [label, y] : plot.horizontalLines) y0 = std::min(y0, y), y1 = std::max(y1, y);
  for (const auto& [label, x] : plot.verticalLines) x0 = std::min(x0, tx(x)), x1 = std::max(x1, tx(x));
  if (!std::isfinite(x0)) x0 = 0, x1 = 1, y0 = 0, y1 = 1;
  if (!(y1 > y0)) y0 -= 0.5, y1 += 0.5;
  if (!(x1 > x0)) x0 -= 0.5, x1 += 0.5;
  y0 = std::min(y0, 0.0);  // plots of sizes and frequencies start at zero
  const double padX = 0.04 * (x1 - x0), padY = 0.06 * (y1 - y0);
  x0 -= padX, x1 += padX, y1 += padY;
  if (y0 < 0) y0 -= padY;
  auto px = [&](double x) { return left + (tx(x) - x0) / (x1 - x0) * plotW; };
  auto py = [&](double y) { return top + (1 - (y - y0) / (y1 - y0)) * plotH; };

  std::ostringstream svg;
  svg << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << width << "\" height=\"" << height
      << "\" viewBox=\"0 0 " << width << ' ' << height << "\" font-family=\"sans-serif\" font-size=\"12\">\n"
      << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n"
      << "<text x=\"" << width / 2 << "\" y=\"22\" text-anchor=\"middle\" font-size=\"15\">" << escapeXml(plot.title)
      << "</text>\n"
      << "<rect x=\"" << left << "\" y=\"" << top << "\" width=\"" << plotW << "\" height=\"" << plotH
      << "\" fill=\"none\" stroke=\"#333\"/>\n";
  for (double t : ticks(y0, y1)) {
    svg << "<line x1=\"" << left << "\" x2=\"" << left + plotW << "\" y1=\"" << py(t) << "\" y2=\"" << py(t)
        << "\" stroke=\"#ddd\"/><text x=\"" << left - 6 << "\" y=\"" << py(t) + 4 << "\" text-anchor=\"end\">"
        << tickLabel(t) << "</text>\n";
  }
  std::vector<double> xTicks;
  if (plot.logX) {
    for (const auto& s : plot.series)
      for (double x : s.x)
        if (x > 0 && std::find(xTicks.begin(), xTicks.end(), x) == xTicks.end()) xTicks.push_back(x);
  } else {
    for (double t : ticks(x0, x1)) xTicks.push_back(t);
  }
  for (double t : xTicks)
    svg << "<line y1=\"" << top << "\" y2=\"" << top + plotH << "\" x1=\"" << px(t) << "\" x2=\"" << px(t)
        << "\" stroke=\"#eee\"/><text x=\"" << px(t) << "\" y=\"" << top + plotH + 16 << "\" text-anchor=\"middle\">"
        << tickLabel(t) << "</text>\n";
  svg << "<text x=\"" << left + plotW / 2 << "\" y=\"" << height - 12 << "\" text-anchor=\"middle\">"
      << escapeXml(plot.xLabel) << "</text>\n<text transform=\"translate(18," << top + plotH / 2
      << ") rotate(-90)\" text-anchor=\"middle\">" << escapeXml(plot.yLabel) << "</text>\n";
  for (const auto& [label, y] : plot.horizontalLines)
    svg << "<line x1=\"" << left << "\" x2=\"" << left + plotW << "\" y1=\"" << py(y) << "\" y2=\"" << py(y)
        << "\" stroke=\"#888\" stroke-dasharray=\"5,4\"/><text x=\"" << left + plotW - 4 << "\" y=\"" << py(y) - 4
        << "\" text-anchor=\"end\" fill=\"#555\">" << escapeXml(label) << "</text>\n";
  for (const auto& [label, x] : plot.verticalLines)
    svg << "<line y1=\"" << top << "\" y2=\"" << top + plotH << "\" x1=\"" << px(x) << "\" x2=\"" << px(x)
        << "\" stroke=\"#888\" stroke-dasharray=\"5,4\"/><text x=\"" << px(x) + 4 << "\" y=\"" << top + 14
        << "\" fill=\"#555\">" << escapeXml(label) << "</text>\n";
  for (std::size_t k = 0; k < plot.series.size(); ++k) {
    const Series& s = plot.series[k];
    std::ostringstream points;
    for (std::size_t i = 0; i < s.x.size(); ++i)
      if (std::isfinite(s.x[i]) && std::isfinite(s.y[i]) && (!plot.logX || s.x[i] > 0))
        points << px(s.x[i]) << ',' << py(s.y[i]) << ' ';
    if (s.filled)
      svg << "<polygon points=\"" << points.str() << "\" fill=\"" << colour(k) << "\" fill-opacity=\"0.3\" stroke=\""
          << colour(k) << "\"/>\n";
    else if (s.line)
      svg << "<polyline points=\"" << points.str() << "\" fill=\"none\" stroke=\"" << colour(k)
          << "\" stroke-width=\"2\"/>\n";
    if (s.points && !s.filled)
      for (std::size_t i = 0; i < s.x.size(); ++i)
        if (std::isfinite(s.x[i]) && std::isfinite(s.y[i]) && (!plot.logX || s.x[i] > 0))
          svg << "<circle cx=\"" << px(s.x[i]) << "\" cy=\"" << py(s.y[i]) << "\" r=\"3.5\" fill=\"" << colour(k)
              << "\"/>\n";
    const double ly = top + 10 + 20 * double(k);
    svg << "<rect x=\"" << left + plotW + 12 << "\" y=\"" << ly - 9 << "\" width=\"14\" height=\"10\" fill=\""
        << colour(k) << "\"/><text x=\"" << left + plotW + 32 << "\" y=\"" << ly << "\">" << escapeXml(s.name)
        << "</text>\n";
  }
  svg << "</svg>\n";
  return svg.str();
}

void Report::heading(const std::string& text) { blocks_.push_back({Block::Heading, text, {}, {}, {}}); }
void Report::paragraph(const std::string& text) { blocks_.push_back({Block::Paragraph, text, {}, {}, {}}); }

void Report::table(const std::string& csvName, const std::vector<std::string>& header,
                   const std::vector<std::vector<std::string>>& rows) {
  blocks_.push_back({Block::Table, "", csvName, header, rows});
  std::string csv;
  auto line = [&](const std::vector<std::string>& cells) {
    for (std::size_t i = 0; i < cells.size(); ++i) csv += (i ? "," : "") + cells[i];
    csv += '\n';
  };
  line(header);
  for (const auto& row : rows) line(row);
  textFiles_[csvName] = csv;
}

void Report::plot(const std::string& svgName, const Plot& plot, const std::string& caption) {
  textFiles_[svgName] = plotSvg(plot);
  blocks_.push_back({Block::Figure, caption, svgName, {}, {}});
}

void Report::image(const std::string& pngName, Image image, const std::string& caption) {
  for (float& v : image.pixels()) v = std::clamp(v, 0.0f, 1.0f);
  images_.emplace_back(pngName, std::move(image));
  blocks_.push_back({Block::Figure, caption, pngName, {}, {}});
}

Status Report::write(const std::filesystem::path& folder) const {
  std::string md = "# " + title_ + "\n\n";
  std::string html = "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>" + escapeXml(title_) +
                     "</title>\n<style>body{font-family:sans-serif;max-width:60em;margin:2em auto;padding:0 1em}"
                     "table{border-collapse:collapse}td,th{border:1px solid #ccc;padding:3px 8px;text-align:right}"
                     "figure{margin:1em 0}img{max-width:100%;image-rendering:pixelated}</style></head><body>\n<h1>" +
                     escapeXml(title_) + "</h1>\n";
  for (const Block& b : blocks_) {
    switch (b.kind) {
      case Block::Heading:
        md += "## " + b.text + "\n\n";
        html += "<h2>" + escapeXml(b.text) + "</h2>\n";
        break;
      case Block::Paragraph:
        md += b.text + "\n\n";
        html += "<p>" + escapeXml(b.text) + "</p>\n";
        break;
      case Block::Table: {
        std::string sep = "|";
        md += "|";
        html += "<table><tr>";
        for (const auto& h : b.header) md += " " + h + " |", sep += "---|", html += "<th>" + escapeXml(h) + "</th>";
        md += "\n" + sep + "\n";
        html += "</tr>\n";
        for (const auto& row : b.rows) {
          md += "|";
          html += "<tr>";
          for (const auto& c : row) md += " " + c + " |", html += "<td>" + escapeXml(c) + "</td>";
          md += "\n";
          html += "</tr>\n";
        }
        md += "\n(table: [" + b.file + "](" + b.file + "))\n\n";
        html += "</table>\n<p><a href=\"" + b.file + "\">" + b.file + "</a></p>\n";
        break;
      }
      case Block::Figure:
        md += "![" + b.text + "](" + b.file + ")\n\n*" + b.text + "*\n\n";
        html += "<figure><img src=\"" + b.file + "\" alt=\"" + escapeXml(b.text) + "\"><figcaption>" +
                escapeXml(b.text) + "</figcaption></figure>\n";
        break;
    }
  }
  md += "Headline numbers: [results.json](results.json)\n";
  html += "<p>Headline numbers: <a href=\"results.json\">results.json</a></p>\n</body></html>\n";
  return writeFolderAtomically(folder, [&](const std::filesystem::path& tmp) -> Status {
    auto text = [&](const std::string& name, const std::string& content) -> Status {
      std::ofstream out(tmp / name, std::ios::binary);
      out << content;
      out.close();
      if (!out) return makeError(ErrorCode::Io, (folder / name).string() + ": cannot write");
      return {};
    };
    LFCAM_TRY(text("report.md", md));
    LFCAM_TRY(text("report.html", html));
    LFCAM_TRY(text("results.json", results_.dump(2) + "\n"));
    for (const auto& [name, content] : textFiles_) LFCAM_TRY(text(name, content));
    for (const auto& [name, image] : images_) {
      ImageWriteOptions options;
      options.sampleType = SampleType::UInt8;
      LFCAM_TRY(writeImage(tmp / name, image, options));
    }
    return Status{};
  });
}

}  // namespace lfcam::experiments
