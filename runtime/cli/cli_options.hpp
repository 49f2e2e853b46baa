#pragma once
// The session's options (runtime/session/session.hpp) as command-line options of nanoview's
// commands: registration only; what the values mean is the session's.
namespace CLI { class App; }

namespace nano::session { struct VariantOptions; struct EffectOptions; }

namespace nano::cli {

// --shell, --prism, --levels, --precision, --lod, --flatten, --no-pipeline-cache.
void add_variant_options(CLI::App& command, session::VariantOptions& options);
// --clip-plane, --clip-box, --time, --effect, --no-effect, --no-scene-effects, --ao-rays, --ao-radius.
void add_effect_options(CLI::App& command, session::EffectOptions& options);

}  // namespace nano::cli
