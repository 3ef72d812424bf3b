#include <limits>

#include "detail/io_common.h"
#include "detail/ply.h"
#include "edgefront/error.h"

namespace edgefront::detail {

namespace fs = std::filesystem;

size_t ply_type_size(PlyType type) {
  switch (type) {
    case PlyType::kInt8:
    case PlyType::kUInt8:
      return 1;
    case PlyType::kInt16:
    case PlyType::kUInt16:
      return 2;
    case PlyType::kInt32:
    case PlyType::kUInt32:
    case PlyType::kFloat32:
      return 4;
    case PlyType::kFloat64:
      return 8;
  }
  return 1;
}

bool ply_type_is_integer(PlyType type) { return type != PlyType::kFloat32 && type != PlyType::kFloat64; }

const char* ply_type_name(PlyType type) {
  switch (type) {
    case PlyType::kInt8:
      return "char";
    case PlyType::kUInt8:
      return "uchar";
    case PlyType::kInt16:
      return "short";
    case PlyType::kUInt16:
      return "ushort";
    case PlyType::kInt32:
      return "int";
    case PlyType::kUInt32:
      return "uint";
    case PlyType::kFloat32:
      return "float";
    case PlyType::kFloat64:
      return "double";
  }
  return "?";
}

int PlyElement::find(std::string_view property_name) const {
  for (size_t i = 0; i < properties.size(); ++i) {
    if (properties[i].name == property_name) return static_cast<int>(i);
  }
  return -1;
}

int PlyHeader::find(std::string_view element_name) const {
  for (size_t i = 0; i < elements.size(); ++i) {
    if (elements[i].name == element_name) return static_cast<int>(i);
  }
  return -1;
}

namespace {

bool parse_type(std::string_view name, PlyType& type) {
  struct Entry {
    const char* name;
    PlyType type;
  };
  static const Entry entries[] = {
      {"char", PlyType::kInt8},      {"int8", PlyType::kInt8},       {"uchar", PlyType::kUInt8},
      {"uint8", PlyType::kUInt8},    {"short", PlyType::kInt16},     {"int16", PlyType::kInt16},
      {"ushort", PlyType::kUInt16},  {"uint16", PlyType::kUInt16},   {"int", PlyType::kInt32},
      {"int32", PlyType::kInt32},    {"uint", PlyType::kUInt32},     {"uint32", PlyType::kUInt32},
      {"float", PlyType::kFloat32},  {"float32", PlyType::kFloat32}, {"double", PlyType::kFloat64},
      {"float64", PlyType::kFloat64}};
  for (const Entry& e : entries) {
    if (name == e.name) {
      type = e.type;
      return true;
    }
  }
  return false;
}

/// Smallest number of bytes one instance of `element` can occupy in the body.
uint64_t min_instance_bytes(const PlyElement& element, PlyFormat format) {
  uint64_t bytes = 0;
  for (const PlyProperty& p : element.properties) {
    if (format == PlyFormat::kAscii) {
      bytes += 2;  // one digit and one separator (or the line end)
    } else {
      bytes += ply_type_size(p.is_list ? p.count_type : p.type);
    }
  }
  return bytes;
}

}  // namespace

bool has_ply_magic(std::string_view data) {
  if (data.substr(0, 3) != "ply") return false;
  const std::string_view rest = data.substr(3);
  return rest.empty() || rest.front() == '\n' || rest.substr(0, 2) == "\r\n";
}

PlyHeader parse_ply_header(std::string_view data, const fs::path& file) {
  if (!has_ply_magic(data)) {
    throw_io(file, "not a PLY file: the first line is not 'ply'");
  }
  PlyHeader header;
  LineReader reader(data);
  std::string_view line;
  reader.next(line);  // the magic
  std::vector<std::string_view> tokens;
  bool have_format = false;
  bool ended = false;
  const auto bad = [&](const std::string& what) {
    throw_io_line(file, reader.line_number(), "bad PLY header: " + what);
  };
  while (reader.next(line)) {
    split_tokens(line, tokens);
    if (tokens.empty()) continue;
    const std::string_view keyword = tokens[0];
    if (keyword == "end_header") {
      if (tokens.size() != 1) bad("unexpected text after 'end_header'");
      ended = true;
      break;
    }
    if (keyword == "comment" || keyword == "obj_info") {
      std::string_view rest = line.substr(line.find(keyword) + keyword.size());
      while (!rest.empty() && (rest.front() == ' ' || rest.front() == '\t')) rest.remove_prefix(1);
      header.comments.emplace_back(rest);
    } else if (keyword == "format") {
      if (have_format) bad("more than one 'format' line");
      if (tokens.size() != 3) bad("expected 'format <ascii|binary_little_endian|binary_big_endian> 1.0'");
      if (tokens[1] == "ascii") {
        header.format = PlyFormat::kAscii;
      } else if (tokens[1] == "binary_little_endian") {
        header.format = PlyFormat::kBinaryLittleEndian;
      } else if (tokens[1] == "binary_big_endian") {
        header.format = PlyFormat::kBinaryBigEndian;
      } else {
        bad("unknown format " + quote(tokens[1]));
      }
      if (tokens[2] != "1.0" && tokens[2] != "1")
        bad("unsupported version " + quote(tokens[2]) + " (expected 1.0)");
      have_format = true;
    } else if (keyword == "element") {
      if (tokens.size() != 3) bad("expected 'element <name> <count>'");
      PlyElement element;
      element.name = std::string(tokens[1]);
      if (!parse_uint64(tokens[2], element.count))
        bad("element count " + quote(tokens[2]) + " is not a non-negative integer");
      element.header_line = reader.line_number();
      if (header.find(element.name) >= 0) bad("element " + quote(element.name) + " is declared twice");
      header.elements.push_back(std::move(element));
    } else if (keyword == "property") {
      if (header.elements.empty()) bad("'property' before any 'element'");
      PlyProperty property;
      if (tokens.size() >= 2 && tokens[1] == "list") {
        if (tokens.size() != 5) bad("expected 'property list <count type> <item type> <name>'");
        property.is_list = true;
        if (!parse_type(tokens[2], property.count_type)) bad("unknown type " + quote(tokens[2]));
        if (!ply_type_is_integer(property.count_type))
          bad("list count type " + quote(tokens[2]) + " is not an integer type");
        if (!parse_type(tokens[3], property.type)) bad("unknown type " + quote(tokens[3]));
        property.name = std::string(tokens[4]);
      } else {
        if (tokens.size() != 3) bad("expected 'property <type> <name>'");
        if (!parse_type(tokens[1], property.type)) bad("unknown type " + quote(tokens[1]));
        property.name = std::string(tokens[2]);
      }
      PlyElement& element = header.elements.back();
      if (element.find(property.name) >= 0) {
        bad("property " + quote(property.name) + " is declared twice in element " + quote(element.name));
      }
      element.properties.push_back(std::move(property));
    } else {
      bad("unknown keyword " + quote(keyword));
    }
  }
  if (!ended) throw_io(file, "bad PLY header: no 'end_header' line (truncated or not a PLY file)");
  if (!have_format) throw_io(file, "bad PLY header: no 'format' line");
  header.body_offset = data.size() - reader.remaining();
  header.body_first_line = reader.line_number() + 1;

  // Refuse counts that cannot fit in the file before anyone reserves memory for them.
  const uint64_t available = data.size() - header.body_offset;
  uint64_t needed = 0;
  for (const PlyElement& element : header.elements) {
    if (element.count == 0) continue;
    if (element.properties.empty()) {
      throw_io_line(file, element.header_line,
                    "bad PLY header: element " + quote(element.name) + " has no properties");
    }
    const uint64_t per_instance = min_instance_bytes(element, header.format);
    const uint64_t limit = std::numeric_limits<uint64_t>::max() / 2;
    if (element.count > (limit - needed) / per_instance) {
      needed = limit;
    } else {
      needed += element.count * per_instance;
    }
    // ascii: the last value of the file may lack its line end
    const uint64_t slack = header.format == PlyFormat::kAscii ? 1 : 0;
    if (needed > available + slack) {
      throw_io_line(file, element.header_line,
                    "the header declares " + std::to_string(element.count) + " " + quote(element.name) +
                        " elements, which need at least " + std::to_string(needed) +
                        " bytes of data, but only " + std::to_string(available) +
                        " bytes follow the header (truncated or corrupt file)");
    }
  }
  return header;
}

PlyBodyReader::PlyBodyReader(std::string_view data, const PlyHeader& header, const fs::path& file)
    : data_(data), header_(header), file_(file), pos_(header.body_offset), line_(header.body_first_line) {
  advance_element();
}

void PlyBodyReader::advance_element() {
  instance_ = 0;
  ++element_;
  while (element_ < static_cast<int>(header_.elements.size()) && header_.elements[element_].count == 0)
    ++element_;
  if (element_ >= static_cast<int>(header_.elements.size())) element_ = -1;
}

std::string PlyBodyReader::where() const {
  std::string out;
  if (header_.format == PlyFormat::kAscii) out = "line " + std::to_string(instance_line_) + " (";
  out += last_element_name_ + " " + std::to_string(last_instance_);
  if (header_.format == PlyFormat::kAscii) out += ")";
  return out;
}

void PlyBodyReader::fail(const std::string& what) const { throw_io(file_, where() + ": " + what); }

void PlyBodyReader::read_instance(PlyInstance& out, const std::vector<bool>& want_list) {
  EF_CHECK(element_ >= 0, "PLY body read past the last element");
  const PlyElement& element = header_.elements[element_];
  last_element_name_ = element.name;
  last_instance_ = instance_;
  out.values.resize(element.properties.size());
  out.lists.resize(element.properties.size());
  for (auto& list : out.lists) list.clear();
  if (header_.format == PlyFormat::kAscii) {
    read_ascii(out, want_list);
  } else {
    read_binary(out, want_list);
  }
  if (++instance_ == element.count) advance_element();
}

void PlyBodyReader::skip_element() {
  if (element_ < 0) return;
  const int current = element_;
  PlyInstance scratch;
  static const std::vector<bool> none;
  while (element_ == current) read_instance(scratch, none);
}

void PlyBodyReader::read_ascii(PlyInstance& out, const std::vector<bool>& want_list) {
  const PlyElement& element = header_.elements[element_];
  std::string_view line;
  for (;;) {
    if (pos_ >= data_.size()) {
      instance_line_ = line_;
      fail("the file ends before " + element.name + " " + std::to_string(instance_) + " of " +
           std::to_string(element.count) + " (truncated file)");
    }
    const size_t end = data_.find('\n', pos_);
    const size_t stop = end == std::string_view::npos ? data_.size() : end;
    line = data_.substr(pos_, stop - pos_);
    pos_ = end == std::string_view::npos ? data_.size() : end + 1;
    instance_line_ = line_++;
    split_tokens(line, tokens_);
    if (!tokens_.empty()) break;
  }
  size_t t = 0;
  for (size_t i = 0; i < element.properties.size(); ++i) {
    const PlyProperty& p = element.properties[i];
    if (t >= tokens_.size()) {
      fail("too few values: expected a value for property " + quote(p.name));
    }
    if (!p.is_list) {
      if (!parse_double(tokens_[t], out.values[i])) {
        fail(bad_number(tokens_[t]) + " for property " + quote(p.name));
      }
      ++t;
      continue;
    }
    uint64_t count = 0;
    if (!parse_uint64(tokens_[t], count)) {
      fail("list length " + quote(tokens_[t]) + " of property " + quote(p.name) +
           " is not a non-negative integer");
    }
    ++t;
    if (count > tokens_.size() - t) {
      fail("property " + quote(p.name) + " declares " + std::to_string(count) +
           " items but the line has only " + std::to_string(tokens_.size() - t) + " values left");
    }
    out.values[i] = static_cast<double>(count);
    const bool keep = i < want_list.size() && want_list[i];
    if (keep) out.lists[i].resize(count);
    for (uint64_t k = 0; k < count; ++k, ++t) {
      double v = 0;
      if (!parse_double(tokens_[t], v)) {
        fail(bad_number(tokens_[t]) + " in list " + quote(p.name));
      }
      if (keep) out.lists[i][k] = v;
    }
  }
  if (t != tokens_.size()) {
    fail("unexpected extra values: the header declares " +
         count_noun(element.properties.size(), "property", "properties") + " for " + quote(element.name) +
         " but the line has more values");
  }
}

double PlyBodyReader::read_binary_value(PlyType type) {
  const size_t size = ply_type_size(type);
  if (data_.size() - pos_ < size) {
    fail("the file ends inside this element (truncated file)");
  }
  const char* p = data_.data() + pos_;
  pos_ += size;
  const bool le = header_.format == PlyFormat::kBinaryLittleEndian;
  switch (type) {
    case PlyType::kInt8:
      return load_bytes<int8_t>(p, le);
    case PlyType::kUInt8:
      return load_bytes<uint8_t>(p, le);
    case PlyType::kInt16:
      return load_bytes<int16_t>(p, le);
    case PlyType::kUInt16:
      return load_bytes<uint16_t>(p, le);
    case PlyType::kInt32:
      return load_bytes<int32_t>(p, le);
    case PlyType::kUInt32:
      return load_bytes<uint32_t>(p, le);
    case PlyType::kFloat32:
      return load_bytes<float>(p, le);
    case PlyType::kFloat64:
      return load_bytes<double>(p, le);
  }
  return 0;
}

void PlyBodyReader::read_binary(PlyInstance& out, const std::vector<bool>& want_list) {
  const PlyElement& element = header_.elements[element_];
  for (size_t i = 0; i < element.properties.size(); ++i) {
    const PlyProperty& p = element.properties[i];
    if (!p.is_list) {
      out.values[i] = read_binary_value(p.type);
      continue;
    }
    const double count_value = read_binary_value(p.count_type);
    if (count_value < 0) {
      fail("negative list length " + std::to_string(static_cast<long long>(count_value)) + " of property " +
           quote(p.name));
    }
    const uint64_t count = static_cast<uint64_t>(count_value);
    const size_t item = ply_type_size(p.type);
    if (count > (data_.size() - pos_) / item) {
      fail("list " + quote(p.name) + " declares " + std::to_string(count) +
           " items, more than the rest of the file holds (truncated or corrupt file)");
    }
    out.values[i] = count_value;
    if (i < want_list.size() && want_list[i]) {
      out.lists[i].resize(count);
      for (uint64_t k = 0; k < count; ++k) out.lists[i][k] = read_binary_value(p.type);
    } else {
      pos_ += count * item;
    }
  }
}

bool PlyBodyReader::has_trailing_data() const {
  if (header_.format != PlyFormat::kAscii) return pos_ < data_.size();
  for (size_t i = pos_; i < data_.size(); ++i) {
    const char c = data_[i];
    if (c != ' ' && c != '\t' && c != '\r' && c != '\n') return true;
  }
  return false;
}

}  // namespace edgefront::detail
