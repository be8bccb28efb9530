#include "TomlNesting.h"

namespace pushout
{
/// The line (from 1) of TOML text at which tables, arrays and dotted keys
/// nest deeper than max_nesting, or 0. A scan of brackets, braces and dots
/// outside strings and comments, made before the parser sees the text.
std::size_t too_deep_at(const std::string& text)
{
  enum class In
  {
    code,
    comment,
    basic,     // "..."
    literal,   // '...'
    ml_basic,  // """..."""
    ml_literal // '''...'''
  };
  In in = In::code;
  std::size_t line = 1, depth = 0, dots = 0;
  for (std::size_t i = 0; i < text.size(); ++i)
  {
    const char c = text[i];
    const bool triple = i + 2 < text.size() && text[i + 1] == c && text[i + 2] == c;
    if (c == '\n')
      ++line;
    switch (in)
    {
    case In::comment:
      if (c == '\n')
        in = In::code;
      continue;
    case In::basic:
    case In::ml_basic:
      if (c == '\\')
        ++i;
      else if (c == '"' && (in == In::basic || triple))
      {
        i += in == In::basic ? 0 : 2;
        in = In::code;
      }
      else if (c == '\n' && in == In::basic)
        in = In::code; // unterminated: the parser reports it
      continue;
    case In::literal:
    case In::ml_literal:
      if (c == '\'' && (in == In::literal || triple))
      {
        i += in == In::literal ? 0 : 2;
        in = In::code;
      }
      else if (c == '\n' && in == In::literal)
        in = In::code;
      continue;
    case In::code:
      break;
    }
    switch (c)
    {
    case '#':
      in = In::comment;
      break;
    case '"':
      in = triple ? In::ml_basic : In::basic;
      i += triple ? 2 : 0;
      break;
    case '\'':
      in = triple ? In::ml_literal : In::literal;
      i += triple ? 2 : 0;
      break;
    case '[':
    case '{':
      ++depth;
      dots = 0;
      break;
    case ']':
    case '}':
      depth -= depth > 0 ? 1 : 0;
      dots = 0;
      break;
    case '.':
      ++dots;
      break;
    case '=':
    case ',':
    case '\n':
      dots = 0;
      break;
    default:
      break;
    }
    if (depth + dots > max_nesting)
      return line;
  }
  return 0;
}
} // namespace pushout
