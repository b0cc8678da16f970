// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesh_bytes.hpp"

#include <libdeflate.h>
#include <zlib.h>

#include <algorithm>
#include <cstdint>
#include <fstream>
#include <memory>
#include <new>
#include <optional>

#include "mesh_text.hpp"

namespace origamic::mesh_input {
namespace {

// Larger than any model a card can show (res_dragon_full, 871,414 triangles, is 34 MB unpacked; this
// holds some 5 million triangles of ASCII): beyond it, a file is refused before it is read, and a
// gzip stream once it unpacks to this much (a 5 MB bomb: 0.8 s and 0.55 GB, where 1 GiB took 10 s
// and 2.1 GB).
constexpr std::uintmax_t kLargestMeshBytes = std::uintmax_t{256} << 20;

// A gzip file's last 4 bytes are its unpacked size, modulo 2^32 (RFC 1952): only a hint, as a
// stream of several members, or a corrupt one, says less or more. Deflate packs at most 1032 to 1, so
// no more than that; 0 where the data is too short or no gzip.
std::size_t unpacked_size_hint(const std::string& packed) {
  if (packed.size() < 18 || static_cast<unsigned char>(packed[0]) != 0x1f ||
      static_cast<unsigned char>(packed[1]) != 0x8b)
    return 0;
  const auto byte = [&](std::size_t from_end) {
    return static_cast<std::uint32_t>(static_cast<unsigned char>(packed[packed.size() - from_end]));
  };
  const std::uint32_t hint = byte(4) | byte(3) << 8 | byte(2) << 16 | byte(1) << 24;
  return static_cast<std::size_t>(
      std::min({std::uintmax_t{hint}, std::uintmax_t{1032} * packed.size(), kLargestMeshBytes + 1}));
}

// A gzip file unpacked at once by libdeflate into the room its size hint makes, where that hint is
// right and the file one member: unpacking res_dragon_full 183 -> 128 ms, bad_motorbike 64 -> 40 ms
// (loading them 616 -> 552 and 393 -> 343 ms, medians of 7); else none (several members, a hint
// that lies, corrupt data, no room), and zlib's stream reads it (read_gzipped).
std::optional<std::string> unpacked_at_once(const std::filesystem::path& file) {
  std::error_code error;
  if (const std::uintmax_t size = std::filesystem::file_size(file, error); error || size > kLargestMeshBytes)
    return std::nullopt;
  const std::string packed = read_plain(file);
  const std::size_t hint = unpacked_size_hint(packed);
  if (hint == 0 || hint > kLargestMeshBytes) return std::nullopt;
  std::string bytes;
  try {
    bytes.resize(hint);
  } catch (const std::bad_alloc&) {
    return std::nullopt;
  }
  const std::unique_ptr<libdeflate_decompressor, decltype(&libdeflate_free_decompressor)> unpacker(
      libdeflate_alloc_decompressor(), &libdeflate_free_decompressor);
  std::size_t read = 0, written = 0;
  if (!unpacker || libdeflate_gzip_decompress_ex(unpacker.get(), packed.data(), packed.size(), bytes.data(),
                                                 bytes.size(), &read, &written) != LIBDEFLATE_SUCCESS)
    return std::nullopt;
  if (read != packed.size() || written != bytes.size()) return std::nullopt;  // another member follows
  return bytes;
}

}  // namespace

std::string read_plain(const std::filesystem::path& file) {
  std::error_code error;
  const std::uintmax_t size = std::filesystem::file_size(file, error);
  if (!error && size > kLargestMeshBytes)
    fail(file, "larger than 256 MiB; no model for a card needs that many triangles");
  std::ifstream in(file, std::ios::binary);
  if (!in) fail(file, "cannot open file");
  // At once where the size is known; a pipe or a special file has none: then to its end, which may
  // be no more than the limit either.
  std::string bytes;
  if (!error) {
    bytes.resize(static_cast<std::size_t>(size));
    in.read(bytes.data(), static_cast<std::streamsize>(size));
    bytes.resize(static_cast<std::size_t>(in.gcount()));
  } else {
    char buffer[1 << 16];
    while (in.read(buffer, sizeof buffer) || in.gcount() > 0) {
      bytes.append(buffer, static_cast<std::size_t>(in.gcount()));
      if (bytes.size() > kLargestMeshBytes)
        fail(file, "larger than 256 MiB; no model for a card needs that many triangles");
    }
  }
  if (in.bad()) fail(file, "cannot read file");
  return bytes;
}

// Several members, a hint that lies or corrupt data: zlib's stream reads all members and names what
// is wrong.
std::string read_gzipped(const std::filesystem::path& file) {
  if (std::optional<std::string> bytes = unpacked_at_once(file)) return std::move(*bytes);
  gzFile gz = gzopen(file.c_str(), "rb");
  if (!gz) fail(file, "cannot open file");
  std::string bytes;
  gzbuffer(gz, 1 << 18);
  constexpr std::size_t kChunk = 1 << 20;
  int n = 0;
  for (;;) {
    const std::size_t size = bytes.size();
    bytes.resize(size + kChunk);
    n = gzread(gz, bytes.data() + size, static_cast<unsigned>(kChunk));
    bytes.resize(size + static_cast<std::size_t>(std::max(n, 0)));
    if (n <= 0) break;
    if (bytes.size() > kLargestMeshBytes) {
      gzclose(gz);
      fail(file, "unpacks to more than 256 MiB; no model for a card needs that many triangles");
    }
  }
  int code = Z_OK;
  const std::string message = gzerror(gz, &code);  // a stream cut short ends reading with Z_BUF_ERROR
  gzclose(gz);
  if (n < 0 || (code != Z_OK && code != Z_STREAM_END)) fail(file, "truncated or corrupt gzip data (" + message + ")");
  return bytes;
}

}  // namespace origamic::mesh_input
