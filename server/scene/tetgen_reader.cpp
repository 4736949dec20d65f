#include "scene/tetgen_reader.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>
#include <vector>

#include "core/math/bounds.hpp"

namespace felt {
namespace {

// A tetrahedron whose volume is below this fraction of its longest edge cubed is flat.
constexpr Real kFlatVolume = 1e-12;

/// The lines of one file that hold data, split into fields, with errors that name the line.
class DataLines {
 public:
  DataLines(std::istream& in, std::string name) : in_(in), name_(std::move(name)) {}

  /// Moves to the next line with data; false at the end of the file.
  bool next() {
    std::string line;
    while (std::getline(in_, line)) {
      ++number_;
      line = line.substr(0, line.find('#'));
      std::istringstream words(line);
      fields_.clear();
      for (std::string word; words >> word;) fields_.push_back(word);
      if (!fields_.empty()) return true;
    }
    return false;
  }
  const std::vector<std::string>& fields() const { return fields_; }

  std::unexpected<std::string> error(const std::string& what) const {
    return std::unexpected(name_ + ":" + std::to_string(number_) + ": " + what);
  }
  std::unexpected<std::string> file_error(const std::string& what) const {
    return std::unexpected(name_ + ": " + what);
  }
  std::unexpected<std::string> columns_error(std::size_t expected) const {
    return error("expected " + std::to_string(expected) + " columns, found " +
                 std::to_string(fields_.size()));
  }

 private:
  std::istream& in_;
  std::string name_;
  std::size_t number_ = 0;
  std::vector<std::string> fields_;
};

/// Parses the whole of `text` as a number; false on anything else.
template <typename Number>
bool parse(const std::string& text, Number& value) {
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  return error == std::errc() && end == text.data() + text.size();
}

/// The header line of either file as non-negative whole numbers.
std::expected<std::vector<long>, std::string> read_header(DataLines& lines,
                                                          const std::string& expected_form) {
  if (!lines.next()) return lines.file_error("empty file, expected \"" + expected_form + "\"");
  std::vector<long> header;
  for (const std::string& field : lines.fields()) {
    long value = 0;
    if (!parse(field, value) || value < 0) {
      return lines.error("bad header \"" + field + "\", expected \"" + expected_form + "\"");
    }
    header.push_back(value);
  }
  return header;
}

/// Reads the numbered records that follow a header: `count` lines of `columns` fields, numbered
/// consecutively from the first record's number, which is returned in `first`.
template <typename ReadRecord>
std::expected<void, std::string> read_records(DataLines& lines, long count, std::size_t columns,
                                              const std::string& what, const std::string& plural,
                                              long& first, ReadRecord&& read_record) {
  for (long r = 0; r < count; ++r) {
    if (!lines.next()) {
      return lines.file_error("expected " + std::to_string(count) + " " + plural + ", found " +
                              std::to_string(r));
    }
    if (lines.fields().size() != columns) return lines.columns_error(columns);
    long number = 0;
    if (!parse(lines.fields()[0], number)) {
      return lines.error("bad " + what + " number \"" + lines.fields()[0] + "\"");
    }
    if (r == 0) first = number;
    if (number != first + r) {
      return lines.error("expected " + what + " " + std::to_string(first + r) + ", found " +
                         std::to_string(number));
    }
    if (auto read = read_record(); !read) return read;
  }
  if (lines.next()) {
    return lines.error("more " + plural + " than the " + std::to_string(count) +
                       " the header announces");
  }
  return {};
}

std::expected<std::vector<Vec3>, std::string> read_nodes(DataLines& lines, long& first) {
  const std::string form = "<nodes> 3 <attributes> <boundary markers 0 or 1>";
  const auto header = read_header(lines, form);
  if (!header) return std::unexpected(header.error());
  if (header->size() != 4) return lines.error("expected \"" + form + "\"");
  const auto [count, dimension, attributes, markers] =
      std::array{(*header)[0], (*header)[1], (*header)[2], (*header)[3]};
  if (count == 0) return lines.error("no nodes (a count of 0 means they are in a .poly file)");
  if (dimension != 3) return lines.error("dimension must be 3, found " + std::to_string(dimension));
  if (markers > 1) return lines.error("boundary markers must be 0 or 1");

  std::vector<Vec3> nodes;
  nodes.reserve(static_cast<std::size_t>(count));
  const auto read = read_records(lines, count, static_cast<std::size_t>(4 + attributes + markers),
                                 "node", "nodes", first, [&]() -> std::expected<void, std::string> {
                                   Vec3 p;
                                   for (int a = 0; a < 3; ++a) {
                                     const std::string& field = lines.fields()[1 + a];
                                     if (!parse(field, p[a]))
                                       return lines.error("bad coordinate \"" + field + "\"");
                                   }
                                   if (!p.allFinite()) return lines.error("non-finite coordinate");
                                   if (!within_bounds(p)) {
                                     return lines.error("coordinate outside ±1e6 m");
                                   }
                                   nodes.push_back(p);
                                   return {};
                                 });
  if (!read) return std::unexpected(read.error());
  return nodes;
}

std::expected<std::vector<Tetrahedron>, std::string> read_tets(DataLines& lines,
                                                               const std::vector<Vec3>& nodes,
                                                               long first_node) {
  const std::string form = "<tetrahedra> 4 <region attributes>";
  const auto header = read_header(lines, form);
  if (!header) return std::unexpected(header.error());
  if (header->size() != 3) return lines.error("expected \"" + form + "\"");
  const auto [count, corners, attributes] = std::array{(*header)[0], (*header)[1], (*header)[2]};
  if (count == 0) return lines.error("no tetrahedra");
  if (corners == 10) {
    return lines.error("10-node (quadratic) tetrahedra are not supported; mesh without -o2");
  }
  if (corners != 4)
    return lines.error("nodes per tetrahedron must be 4, found " + std::to_string(corners));

  std::vector<Tetrahedron> tets;
  tets.reserve(static_cast<std::size_t>(count));
  long first_tet = 0;
  const auto read = read_records(
      lines, count, static_cast<std::size_t>(5 + attributes), "tetrahedron", "tetrahedra",
      first_tet, [&]() -> std::expected<void, std::string> {
        Tetrahedron t;
        for (int c = 0; c < 4; ++c) {
          const std::string& field = lines.fields()[1 + c];
          long index = 0;
          if (!parse(field, index)) return lines.error("bad node index \"" + field + "\"");
          const long zero_based = index - first_node;
          if (zero_based < 0 || zero_based >= static_cast<long>(nodes.size())) {
            return lines.error("node index " + field + " out of range");
          }
          t[c] = static_cast<std::uint32_t>(zero_based);
        }
        Real longest = 0;
        for (int a = 0; a < 4; ++a) {
          for (int b = a + 1; b < 4; ++b) {
            longest = std::max(longest, (nodes[t[a]] - nodes[t[b]]).norm());
          }
        }
        if (std::abs(signed_volume(nodes, t)) <= kFlatVolume * longest * longest * longest) {
          return lines.error("tetrahedron " + lines.fields()[0] + " has zero volume");
        }
        tets.push_back(t);
        return {};
      });
  if (!read) return std::unexpected(read.error());
  return tets;
}

}  // namespace

std::expected<TetMesh, std::string> read_tetgen(std::istream& node, const std::string& node_name,
                                                std::istream& ele, const std::string& ele_name) {
  DataLines node_lines(node, node_name);
  long first_node = 0;
  auto nodes = read_nodes(node_lines, first_node);
  if (!nodes) return std::unexpected(nodes.error());
  DataLines ele_lines(ele, ele_name);
  auto tets = read_tets(ele_lines, *nodes, first_node);
  if (!tets) return std::unexpected(tets.error());
  TetMesh mesh{std::move(*nodes), std::move(*tets)};
  orient_positive(mesh);
  return mesh;
}

std::expected<TetMesh, std::string> read_tetgen_files(const std::filesystem::path& path) {
  std::filesystem::path base = path;
  if (base.extension() == ".node" || base.extension() == ".ele") base.replace_extension();
  const std::filesystem::path node_file = base.string() + ".node";
  const std::filesystem::path ele_file = base.string() + ".ele";
  std::ifstream node(node_file);
  if (!node) return std::unexpected("cannot open " + node_file.filename().string());
  std::ifstream ele(ele_file);
  if (!ele) return std::unexpected("cannot open " + ele_file.filename().string());
  return read_tetgen(node, node_file.filename().string(), ele, ele_file.filename().string());
}

}  // namespace felt
