// `nanoview validate FILE [--json]`: structural and semantic validation of a package, no GPU needed.
#include <cstdio>
#include <string>

#include <nlohmann/json.hpp>

#include "format/validator.hpp"
#include "runtime/cli/commands.hpp"

namespace nano::cli {
namespace {

using format::SectionEntry;

const char* codec_name(std::uint16_t codec) {
  switch (static_cast<format::Codec>(codec)) {
    case format::Codec::zstd: return "zstd";
    case format::Codec::draco: return "draco";
    case format::Codec::none: break;
  }
  return "none";
}

// Records in a section, or nothing for kinds this reader does not know.
std::optional<std::uint64_t> record_count(const format::Package& p, const SectionEntry& e) {
  if (!format::is_known_section_kind(e.kind)) return std::nullopt;
  return p.record_count(static_cast<format::SectionKind>(e.kind));
}

std::string version_of(const format::Package& p) {
  return std::to_string(p.header().version_major) + "." + std::to_string(p.header().version_minor);
}

nlohmann::json summary_json(const format::Package& p) {
  nlohmann::json sections = nlohmann::json::array();
  std::uint64_t stored = 0, raw = 0;
  for (const SectionEntry& e : p.entries()) {
    const auto count = record_count(p, e);
    sections.push_back({{"kind", format::section_kind_name(e.kind)},
                        {"offset", e.offset},
                        {"stored", e.stored_size},
                        {"raw", e.raw_size},
                        {"codec", codec_name(e.codec)},
                        {"count", count ? nlohmann::json(*count) : nlohmann::json(nullptr)}});
    stored += e.stored_size;
    raw += e.raw_size;
  }
  return {{"valid", true},
          {"file", p.name()},
          {"version", version_of(p)},
          {"sections", sections},
          {"totals", {{"sections", p.entries().size()}, {"file_size", p.file_size()}, {"stored", stored}, {"raw", raw}}}};
}

std::string summary_line(const format::Package& p) {
  std::uint64_t raw = 0;
  std::string counts;
  for (const SectionEntry& e : p.entries()) {
    raw += e.raw_size;
    const auto count = record_count(p, e);
    counts += (counts.empty() ? "" : ", ") + format::section_kind_name(e.kind) + " " +
              (count ? std::to_string(*count) : std::to_string(e.raw_size) + " B");
  }
  return p.name() + ": valid .nup " + version_of(p) + ", " + std::to_string(p.entries().size()) + " sections, " +
         std::to_string(p.file_size()) + " bytes (" + std::to_string(raw) + " raw)" + (counts.empty() ? "" : ": " + counts);
}

nlohmann::json error_json(const InputError& e) {
  nlohmann::json j = {{"valid", false}, {"error", e.what()}};
  if (const auto* pe = dynamic_cast<const format::PackageError*>(&e)) {
    j["rule"] = format::rule_name(pe->code());
    const format::Location& at = pe->location();
    j["section"] = at.section_kind ? nlohmann::json(format::section_kind_name(*at.section_kind)) : nlohmann::json(nullptr);
    j["offset"] = at.offset;
    j["decompressed"] = at.decompressed;
  }
  return j;
}

}  // namespace

void add_validate_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("validate", "Check a package's structure, checksums and every index (no GPU)");
  auto file = std::make_shared<std::string>();
  auto json = std::make_shared<bool>(false);
  cmd->add_option("FILE", *file, "package (.nup)")->required();
  cmd->add_flag("--json", *json, "print a JSON report on stdout");
  cmd->callback([file, json] {
    try {
      const format::Package p = format::open_validated(*file);
      std::printf("%s\n", *json ? summary_json(p).dump(2).c_str() : summary_line(p).c_str());
    } catch (const InputError& e) {
      if (!*json) throw;  // main prints "nanoview: error: FILE:WHERE: RULE" and exits 1
      std::printf("%s\n", error_json(e).dump(2).c_str());
      std::fprintf(stderr, "nanoview: error: %s\n", e.what());
      throw CLI::RuntimeError(1);
    }
  });
}

}  // namespace nano::cli
