#include "msp/svg_canvas.h"

#include <cmath>
#include <cstdio>

#include <ricci/mesh/errors.h>

namespace msp {

SvgCanvas::SvgCanvas(const Eigen::AlignedBox2d& view, double width_px, double rotation)
    : view_(view), rotation_(Eigen::Rotation2Dd(rotation).toRotationMatrix()), width_(width_px) {
  const Eigen::Vector2d size = view.sizes();
  if (view.isEmpty() || !(size.x() > 0) || !(size.y() > 0) || !(width_px > 0) ||
      !size.allFinite()) {
    throw ricci::InvalidInputError("SVG canvas: empty or non-finite view, or width " +
                                   std::to_string(width_px));
  }
  scale_ = width_px / size.x();
  height_ = size.y() * scale_;
}

Eigen::Vector2d SvgCanvas::px(const Eigen::Vector2d& world) const {
  const Eigen::Vector2d p = rotation_ * world;
  return {(p.x() - view_.min().x()) * scale_, (view_.max().y() - p.y()) * scale_};
}

std::string SvgCanvas::path_data(const Eigen::MatrixX2d& points, bool closed) const {
  std::string d;
  d.reserve(static_cast<size_t>(points.rows()) * 14);
  for (Eigen::Index i = 0; i < points.rows(); ++i) {
    const Eigen::Vector2d p = px(points.row(i).transpose());
    d += i == 0 ? "M" : "L";
    d += svg_number(p.x());
    d += ' ';
    d += svg_number(p.y());
  }
  if (closed && points.rows() > 0) d += "Z";
  return d;
}

void SvgCanvas::add(const std::string& element) {
  body_ += element;
  body_ += '\n';
}

std::string svg_number(double value) {
  double rounded = std::round(value * 10.0) / 10.0;
  if (rounded == 0.0) rounded = 0.0;  // no "-0"
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.1f", rounded);
  std::string s(buffer);
  if (s.size() > 2 && s.compare(s.size() - 2, 2, ".0") == 0) s.resize(s.size() - 2);
  return s;
}

std::string svg_escape(const std::string& text) {
  std::string out;
  for (char c : text) {
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

std::string captioned_svg(const SvgCanvas& canvas, const std::vector<std::string>& lines,
                          int text_size) {
  const double line_height = 19,
               caption_height = line_height * static_cast<double>(lines.size()) + 12;
  const std::string w = svg_number(canvas.width()),
                    h = svg_number(canvas.height() + caption_height);
  std::string svg = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  svg += "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" + w + "\" height=\"" + h +
         "\" viewBox=\"0 0 " + w + " " + h + "\">\n";
  svg += "<rect width=\"100%\" height=\"100%\" fill=\"#ffffff\"/>\n";
  svg += "<g font-family=\"DejaVu Sans, sans-serif\" fill=\"#222\">\n";
  for (size_t i = 0; i < lines.size(); ++i) {
    svg += "<text x=\"10\" y=\"" + svg_number(line_height * static_cast<double>(i + 1)) +
           "\" font-size=\"" +
           (i == 0 ? std::string("16\" font-weight=\"bold") : std::to_string(text_size)) +
           "\">" + svg_escape(lines[i]) + "</text>\n";
  }
  svg += "</g>\n";
  svg += "<svg x=\"0\" y=\"" + svg_number(caption_height) + "\" width=\"" + w + "\" height=\"" +
         svg_number(canvas.height()) + "\" viewBox=\"0 0 " + w + " " + svg_number(canvas.height()) +
         "\" overflow=\"hidden\">\n";
  svg += canvas.body();
  svg += "</svg>\n</svg>\n";
  return svg;
}

}  // namespace msp
