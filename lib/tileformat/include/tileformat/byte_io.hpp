// Little-endian byte writer and bounds-checked reader: the one byte codec of
// the project, for the package's blobs and for every builder's scratch and
// staging data (docs/architecture.md). Readers never cast structs onto bytes;
// every read checks the remaining length first and throws FormatError citing
// the section the caller is decoding.
#pragma once

#include <bit>
#include <cstdint>
#include <cstring>
#include <span>
#include <string>
#include <vector>

#include "tileformat/error.hpp"

namespace tileformat {

class ByteWriter {
 public:
  void u8(uint8_t v) { out_.push_back(v); }
  void u16(uint16_t v) { put(v); }
  void u32(uint32_t v) { put(v); }
  void i32(int32_t v) { put(static_cast<uint32_t>(v)); }
  void u64(uint64_t v) { put(v); }
  void f64(double v) { put(std::bit_cast<uint64_t>(v)); }
  // LEB128: 7 bits per byte, low bits first.
  void varint(uint64_t v) {
    while (v >= 0x80) {
      out_.push_back(static_cast<uint8_t>(v | 0x80));
      v >>= 7;
    }
    out_.push_back(static_cast<uint8_t>(v));
  }
  void svarint(int64_t v) {
    varint((static_cast<uint64_t>(v) << 1) ^ static_cast<uint64_t>(v >> 63));
  }
  void bytes(std::span<const uint8_t> b) { out_.insert(out_.end(), b.begin(), b.end()); }
  size_t size() const { return out_.size(); }
  std::vector<uint8_t> take() { return std::move(out_); }

 private:
  template <typename T>
  void put(T v) {
    for (size_t i = 0; i < sizeof(T); ++i)
      out_.push_back(static_cast<uint8_t>(v >> (8 * i)));
  }
  std::vector<uint8_t> out_;
};

class ByteReader {
 public:
  // `what` names the structure being read, `section` its spec section.
  ByteReader(std::span<const uint8_t> in, std::string what, std::string section)
      : in_(in), what_(std::move(what)), section_(std::move(section)) {}

  uint8_t u8() { return static_cast<uint8_t>(get<uint8_t>()); }
  uint16_t u16() { return get<uint16_t>(); }
  uint32_t u32() { return get<uint32_t>(); }
  int32_t i32() { return static_cast<int32_t>(get<uint32_t>()); }
  uint64_t u64() { return get<uint64_t>(); }
  double f64() { return std::bit_cast<double>(get<uint64_t>()); }
  uint64_t varint() {
    uint64_t v = 0;
    for (int shift = 0; shift < 64; shift += 7) {
      const uint8_t b = u8();
      v |= uint64_t{b & 0x7fu} << shift;
      if (!(b & 0x80)) return v;
    }
    fail("varint longer than 10 bytes");
  }
  int64_t svarint() {
    const uint64_t u = varint();
    return static_cast<int64_t>(u >> 1) ^ -static_cast<int64_t>(u & 1);
  }
  std::span<const uint8_t> bytes(size_t n) {
    need(n);
    auto s = in_.subspan(pos_, n);
    pos_ += n;
    return s;
  }
  size_t remaining() const { return in_.size() - pos_; }
  size_t position() const { return pos_; }
  void set_section(std::string section) { section_ = std::move(section); }

  [[noreturn]] void fail(const std::string& msg) const {
    throw FormatError(section_, what_ + ": " + msg);
  }
  void expect_end() const {
    if (remaining() != 0) fail(std::to_string(remaining()) + " trailing bytes");
  }

 private:
  void need(size_t n) const {
    if (remaining() < n)
      fail("truncated at byte " + std::to_string(pos_) + " (need " + std::to_string(n) + ", have " +
           std::to_string(remaining()) + ")");
  }
  template <typename T>
  T get() {
    need(sizeof(T));
    T v = 0;
    for (size_t i = 0; i < sizeof(T); ++i)
      v |= static_cast<T>(T{in_[pos_ + i]} << (8 * i));
    pos_ += sizeof(T);
    return v;
  }
  std::span<const uint8_t> in_;
  size_t pos_ = 0;
  std::string what_;
  std::string section_;
};

}  // namespace tileformat
