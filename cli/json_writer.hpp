// A minimal JSON writer for the CLI's --json output (objects, arrays,
// strings, numbers, booleans; non-finite numbers become null).
#pragma once

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace fcsolve_cli {

class JsonWriter {
 public:
  JsonWriter& begin_object() { open('{'); return *this; }
  JsonWriter& end_object() { close('}'); return *this; }
  JsonWriter& begin_array() { open('['); return *this; }
  JsonWriter& end_array() { close(']'); return *this; }
  JsonWriter& key(const std::string& k) {
    comma();
    string_literal(k);
    out_ += ':';
    after_key_ = true;
    return *this;
  }
  JsonWriter& value(const std::string& s) { comma(); string_literal(s); return *this; }
  JsonWriter& value(const char* s) { return value(std::string(s)); }
  JsonWriter& value(bool b) { comma(); out_ += b ? "true" : "false"; return *this; }
  JsonWriter& value(double x) {
    comma();
    if (!std::isfinite(x)) {
      out_ += "null";
    } else {
      char buf[40];
      std::snprintf(buf, sizeof buf, "%.17g", x);
      out_ += buf;
    }
    return *this;
  }
  JsonWriter& value(long long i) { comma(); out_ += std::to_string(i); return *this; }
  JsonWriter& value(int i) { return value(static_cast<long long>(i)); }
  JsonWriter& value(long i) { return value(static_cast<long long>(i)); }
  template <class T>
  JsonWriter& field(const std::string& k, const T& v) { key(k); return value(v); }
  JsonWriter& values(const std::vector<double>& xs) {
    begin_array();
    for (double x : xs) value(x);
    return end_array();
  }
  const std::string& str() const { return out_; }

 private:
  void open(char c) { comma(); out_ += c; first_.push_back(true); }
  void close(char c) { out_ += c; first_.pop_back(); }
  void comma() {
    if (after_key_) { after_key_ = false; return; }
    if (!first_.empty()) {
      if (!first_.back()) out_ += ',';
      first_.back() = false;
    }
  }
  // ASCII output: a UTF-8 sequence becomes one \uXXXX escape (a surrogate
  // pair above U+FFFF, RFC 8259 sec. 7); a byte that is not valid UTF-8
  // (CubeH8's title has a stray 0xA8) becomes U+FFFD, the replacement character.
  void string_literal(const std::string& s) {
    out_ += '"';
    for (std::size_t k = 0; k < s.size();) {
      const unsigned char c = static_cast<unsigned char>(s[k]);
      switch (c) {
        case '"': out_ += "\\\""; ++k; continue;
        case '\\': out_ += "\\\\"; ++k; continue;
        case '\n': out_ += "\\n"; ++k; continue;
        case '\t': out_ += "\\t"; ++k; continue;
        case '\r': out_ += "\\r"; ++k; continue;
        default: break;
      }
      if (c >= 0x20 && c < 0x7f) {
        out_ += static_cast<char>(c);
        ++k;
        continue;
      }
      std::size_t length = 0;
      const char32_t code = decode_utf8(s, k, length);
      k += length;
      escape(code);
    }
    out_ += '"';
  }
  /// The code point at s[k] and its length in bytes; U+FFFD (length 1) when
  /// the bytes there are not a valid, shortest-form UTF-8 sequence.
  static char32_t decode_utf8(const std::string& s, std::size_t k, std::size_t& length) {
    const auto byte = [&](std::size_t j) { return static_cast<unsigned char>(s[j]); };
    const unsigned char c = byte(k);
    length = 1;
    std::size_t extra = 0;
    char32_t code = 0, least = 0;
    if (c < 0x80) return c;
    if ((c & 0xE0) == 0xC0) { extra = 1; code = c & 0x1F; least = 0x80; }
    else if ((c & 0xF0) == 0xE0) { extra = 2; code = c & 0x0F; least = 0x800; }
    else if ((c & 0xF8) == 0xF0) { extra = 3; code = c & 0x07; least = 0x10000; }
    else return 0xFFFD;
    if (k + extra >= s.size()) return 0xFFFD;  // sequence cut short by the end
    for (std::size_t j = 1; j <= extra; ++j) {
      if ((byte(k + j) & 0xC0) != 0x80) return 0xFFFD;
      code = (code << 6) | (byte(k + j) & 0x3F);
    }
    if (code < least || code > 0x10FFFF || (code >= 0xD800 && code <= 0xDFFF)) return 0xFFFD;
    length = extra + 1;
    return code;
  }
  void escape(char32_t code) {
    char buf[16];
    if (code > 0xFFFF) {
      code -= 0x10000;
      std::snprintf(buf, sizeof buf, "\\u%04x\\u%04x", unsigned(0xD800 + (code >> 10)),
                    unsigned(0xDC00 + (code & 0x3FF)));
    } else {
      std::snprintf(buf, sizeof buf, "\\u%04x", unsigned(code));
    }
    out_ += buf;
  }
  std::string out_;
  std::vector<bool> first_;
  bool after_key_ = false;
};

}  // namespace fcsolve_cli
