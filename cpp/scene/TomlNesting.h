// How deep a scene's TOML may nest, checked before the TOML parser sees the
// text (deeper text is not a scene, and would exhaust the parser's stack).
#pragma once

#include <cstddef>
#include <string>

namespace pushout
{
/// Levels of tables, arrays and dotted keys a scene may nest (a scene needs
/// 3: `[[interface]]`, `k`; deeper text is not a scene, and would exhaust the
/// TOML parser's stack).
constexpr std::size_t max_nesting = 32;

/// The line (from 1) of TOML text at which tables, arrays and dotted keys
/// nest deeper than max_nesting, or 0. A scan of brackets, braces and dots
/// outside strings and comments, made before the parser sees the text.
std::size_t too_deep_at(const std::string& text);
} // namespace pushout
