#include "bake/structure/structure_text.hpp"

#include <zlib.h>

#include <cstdio>
#include <cstring>
#include <memory>

#include "common/error.hpp"

namespace nano::structure {
namespace {

std::string read_raw_bytes(const std::filesystem::path& path) {
  const std::string name = path.string();
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw InputError(name, "", "file does not exist");
  if (std::filesystem::is_directory(path, ec)) throw InputError(name, "", "is a directory, not a structure file");
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> f(std::fopen(name.c_str(), "rb"), &std::fclose);
  if (!f) throw InputError(name, "", std::string("cannot open file: ") + std::strerror(errno));
  std::string bytes;
  const auto size = std::filesystem::file_size(path, ec);
  if (!ec) bytes.reserve(static_cast<std::size_t>(size));
  char buffer[1 << 16];
  std::size_t n;
  while ((n = std::fread(buffer, 1, sizeof buffer, f.get())) > 0) bytes.append(buffer, n);
  if (std::ferror(f.get())) throw InputError(name, "", "read error");
  return bytes;
}

bool is_gzip(const std::string& bytes) {
  return bytes.size() >= 2 && static_cast<unsigned char>(bytes[0]) == 0x1f &&
         static_cast<unsigned char>(bytes[1]) == 0x8b;
}

// Inflates every gzip member (concatenated members are legal and produced by some tools).
std::string inflate_gzip(const std::string& compressed, const std::string& name) {
  z_stream stream{};
  if (inflateInit2(&stream, 15 + 32) != Z_OK) throw InputError(name, "", "cannot initialise zlib");
  std::string out;
  out.reserve(compressed.size() * 4);
  stream.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(compressed.data()));
  stream.avail_in = static_cast<uInt>(compressed.size());
  char buffer[1 << 16];
  int status = Z_OK;
  for (;;) {
    stream.next_out = reinterpret_cast<Bytef*>(buffer);
    stream.avail_out = sizeof buffer;
    status = inflate(&stream, Z_NO_FLUSH);
    out.append(buffer, sizeof buffer - stream.avail_out);
    if (status == Z_STREAM_END) {
      if (stream.avail_in == 0) break;
      inflateReset(&stream);  // another member follows
      continue;
    }
    // All input consumed without reaching the end of the stream: the file was cut short.
    const bool starved = stream.avail_in == 0 && (status == Z_BUF_ERROR || (status == Z_OK && stream.avail_out != 0));
    if (starved) {
      inflateEnd(&stream);
      throw InputError(name, "byte " + std::to_string(compressed.size()), "truncated gzip stream");
    }
    if (status != Z_OK && status != Z_BUF_ERROR) {
      const std::string why = stream.msg ? stream.msg : "invalid data";
      // Counted in the file, not in the member (total_in starts again at each member).
      const std::size_t at = compressed.size() - stream.avail_in;
      inflateEnd(&stream);
      throw InputError(name, "byte " + std::to_string(at), "corrupt gzip stream: " + why);
    }
  }
  inflateEnd(&stream);
  return out;
}

// Text files never contain NUL; control bytes other than whitespace mean binary data too.
void reject_binary(const std::string& text, const std::string& name) {
  std::size_t line = 1;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const unsigned char c = static_cast<unsigned char>(text[i]);
    if (c == '\n') ++line;
    else if (c < 0x20 && c != '\t' && c != '\r' && c != '\f' && c != '\v') {
      throw InputError(name, "line " + std::to_string(line),
                       "binary data (control byte 0x" + [c] {
                         char hex[3];
                         std::snprintf(hex, sizeof hex, "%02x", c);
                         return std::string(hex);
                       }() + " at byte " + std::to_string(i) + "): not a PDB or mmCIF text file");
    }
  }
}

}  // namespace

std::string structure_text_from_bytes(std::string bytes, const std::string& name) {
  if (is_gzip(bytes)) bytes = inflate_gzip(bytes, name);
  reject_binary(bytes, name);
  return bytes;
}

std::string read_structure_text(const std::filesystem::path& path) {
  return structure_text_from_bytes(read_raw_bytes(path), path.string());
}

}  // namespace nano::structure
