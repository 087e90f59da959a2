// Rectangles of the case-file key tables (case_fields.hpp).

#include "io/case_fields.hpp"

namespace hfdda::io::schema {

const Table<Rect>& rect_table() {
  static const Table<Rect> table{
      "Rectangles (`domain.outer`, `domain.inner`, `materials[].box`, "
      "`breakable_patterns[].region`)",
      "A rectangle is given whole, all four keys, and replaces the previous one; "
      "xmin < xmax and ymin < ymax.",
      {required(number<Rect>({"xmin", "m", "", "left edge"}, &Rect::xmin, magnitude_up_to(kMaxCoordinate))),
       required(number<Rect>({"xmax", "m", "", "right edge"}, &Rect::xmax, magnitude_up_to(kMaxCoordinate))),
       required(number<Rect>({"ymin", "m", "", "bottom edge"}, &Rect::ymin, magnitude_up_to(kMaxCoordinate))),
       required(number<Rect>({"ymax", "m", "", "top edge"}, &Rect::ymax, magnitude_up_to(kMaxCoordinate)))}};
  return table;
}

Rect read_rect(FileReader& r, const YAML::Node& n, const std::string& key) {
  Rect rect;
  r.forget(key + ".");
  parse_map(r, n, key, rect_table(), rect);
  if (!(rect.xmin < rect.xmax))
    r.fail(n["xmax"], key + ".xmax",
           "must be > xmin (got xmin " + format_number(rect.xmin) + ", xmax " +
               format_number(rect.xmax) + ")");
  if (!(rect.ymin < rect.ymax))
    r.fail(n["ymax"], key + ".ymax",
           "must be > ymin (got ymin " + format_number(rect.ymin) + ", ymax " +
               format_number(rect.ymax) + ")");
  return rect;
}

KeyDoc rect_doc(const Doc& d, std::string default_text, std::string allowed) {
  KeyDoc doc = key_doc(d, "rectangle", std::move(default_text), std::move(allowed));
  doc.child = [] { return section_doc(rect_table()); };
  return doc;
}

}  // namespace hfdda::io::schema
