#pragma once
// A minimal SVG canvas: maps a box of the plane (y up) onto pixels (y down) and collects
// elements; coordinates are written with one decimal, enough at 1000 px and small on disk.
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace msp {

class SvgCanvas {
 public:
  /// World points are first turned by `rotation` (radians, about the origin); `view` (in the
  /// turned frame) fills `width_px` pixels; the height follows the aspect ratio.
  /// \throw ricci::InvalidInputError for an empty view or a non-positive width.
  SvgCanvas(const Eigen::AlignedBox2d& view, double width_px, double rotation = 0.0);

  [[nodiscard]] double width() const { return width_; }
  [[nodiscard]] double height() const { return height_; }
  [[nodiscard]] double pixels_per_unit() const { return scale_; }
  [[nodiscard]] Eigen::Vector2d px(const Eigen::Vector2d& world) const;

  /// "M x y L x y ..." of world points (rows), closed with Z when asked.
  [[nodiscard]] std::string path_data(const Eigen::MatrixX2d& points, bool closed) const;
  /// Appends one element (already formatted) to the drawing.
  void add(const std::string& element);
  [[nodiscard]] const std::string& body() const { return body_; }

 private:
  Eigen::AlignedBox2d view_;
  Eigen::Matrix2d rotation_ = Eigen::Matrix2d::Identity();
  double width_ = 0, height_ = 0, scale_ = 1;
  std::string body_;
};

/// One decimal, no trailing ".0", "-0" written as "0".
[[nodiscard]] std::string svg_number(double value);
/// Escapes &, <, >, " for text and attribute values.
[[nodiscard]] std::string svg_escape(const std::string& text);

/// A whole SVG document: `lines` of caption on top (the first in bold 16 px, the others in
/// `text_size` px, 19 px apart) and the canvas's drawing below them in a nested viewport,
/// which clips whatever the drawing puts outside the canvas.
[[nodiscard]] std::string captioned_svg(const SvgCanvas& canvas,
                                        const std::vector<std::string>& lines, int text_size);

}  // namespace msp
