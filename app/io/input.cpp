#include "app/io/input.h"

#include "app/io/text.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <set>
#include <string_view>
#include <system_error>

#include <unistd.h>

namespace demvv
{
namespace
{
std::string size_text(std::uintmax_t bytes)
{
  char text[32];
  if (bytes >= (std::uintmax_t{1} << 30))
    std::snprintf(text, sizeof text, "%.3g GiB", double(bytes) / double(std::uintmax_t{1} << 30));
  else
    std::snprintf(text, sizeof text, "%.3g MiB", double(bytes) / double(std::uintmax_t{1} << 20));
  return text;
}

/// Deepest nesting of arrays and objects in JSON text (strings skipped).
int json_depth(const std::string &text)
{
  int depth = 0, deepest = 0;
  bool in_string = false, escape = false;
  for (const char c : text)
  {
    if (in_string)
    {
      if (escape)
        escape = false;
      else if (c == '\\')
        escape = true;
      else if (c == '"')
        in_string = false;
    }
    else if (c == '"')
      in_string = true;
    else if (c == '[' || c == '{')
      deepest = std::max(deepest, ++depth);
    else if (c == ']' || c == '}')
      --depth;
  }
  return deepest;
}
} // namespace

std::string read_input(const std::string &path, const std::string &what, std::uintmax_t max_bytes)
{
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (ec || !fs::exists(status))
    throw DeckError(path + ": cannot open the " + what + " (does it exist and is it readable?)");
  if (!fs::is_regular_file(status))
    throw DeckError(path + ": is not a regular file (a directory, device or pipe): expected a " + what);
  const std::uintmax_t size = fs::file_size(path, ec);
  if (ec)
    throw DeckError(path + ": cannot open the " + what + " (does it exist and is it readable?)");
  if (size > max_bytes)
    throw DeckError(path + ": the " + what + " has " + size_text(size) + ": expected at most " + size_text(max_bytes));
  std::ifstream in(path, std::ios::binary);
  if (!in)
    throw DeckError(path + ": cannot open the " + what + " (does it exist and is it readable?)");
  std::string text(static_cast<std::size_t>(size), '\0');
  in.read(text.data(), static_cast<std::streamsize>(size));
  text.resize(static_cast<std::size_t>(in.gcount()));
  if (in.bad())
    throw DeckError(path + ": cannot read the " + what);
  return as_utf8_text(std::move(text), path, what);
}

std::string as_utf8_text(std::string text, const std::string &path, const std::string &what)
{
  const auto starts = [&](std::string_view mark) { return text.compare(0, mark.size(), mark) == 0; };
  using namespace std::string_view_literals;
  const char *encoding = starts("\xFF\xFE\x00\x00"sv) || starts("\x00\x00\xFE\xFF"sv) ? "UTF-32"
                         : starts("\xFF\xFE"sv) || starts("\xFE\xFF"sv)               ? "UTF-16"
                                                                                      : nullptr;
  if (encoding)
    throw DeckError(path + ": the " + what + " is " + encoding +
                    " text (its byte-order mark says so): expected UTF-8 or ASCII (save it as UTF-8)");
  // ASCII in UTF-16 or UTF-32 without a byte-order mark: every other (or
  // every fourth) byte of the first characters is NUL.  A stray NUL inside
  // a value is left to the parser, which names its line and column.
  if (text.size() >= 4 &&
      ((text[0] != 0 && text[1] == 0 && text[3] == 0) || (text[0] == 0 && text[2] == 0 && text[1] != 0) ||
       (text[0] == 0 && text[1] == 0 && text[3] != 0)))
    throw DeckError(path + ": the " + what +
                    " looks like UTF-16 or UTF-32 text without a byte-order mark (its first characters alternate with "
                    "NUL bytes): expected UTF-8 or ASCII (save it as UTF-8)");
  if (starts("\xEF\xBB\xBF"sv))
    text.erase(0, 3); // the UTF-8 byte-order mark some editors write: the text itself is what is expected
  if (text.find('\r') != std::string::npos && text.find('\n') == std::string::npos)
    throw DeckError(path + ": the " + what +
                    " ends its lines with carriage returns alone (classic Mac OS): expected LF or CRLF line ends "
                    "(convert it with tr '\\r' '\\n')");
  return text;
}

double json_number(const nlohmann::json &j, const char *key)
{
  return j.is_object() && j.contains(key) && j[key].is_number() ? j[key].get<double>() : nan;
}

nlohmann::json parse_json_input(const std::string &text, const std::string &path, const std::string &what)
{
  if (json_depth(text) > max_json_depth)
    throw DeckError(path + ": arrays or objects nested more than " + std::to_string(max_json_depth) +
                    " levels deep: expected a " + what);
  // nlohmann keeps the last of two equal keys in an object; a deck or
  // sample that names a key twice is refused instead (one of the two values
  // would be ignored without a word).
  std::vector<std::set<std::string>> keys_of_open_objects;
  const auto refuse_repeated_keys = [&](int, nlohmann::json::parse_event_t event, nlohmann::json &parsed)
  {
    using Event = nlohmann::json::parse_event_t;
    if (event == Event::object_start)
      keys_of_open_objects.emplace_back();
    else if (event == Event::object_end)
      keys_of_open_objects.pop_back();
    else if (event == Event::key && !keys_of_open_objects.back().insert(parsed.get<std::string>()).second)
      throw DeckError(path + ": key '" + escaped(parsed.get<std::string>()) +
                      "' appears twice in one object: expected each key once (the last would win silently) in a " +
                      what);
    return true;
  };
  try
  {
    return nlohmann::json::parse(text, refuse_repeated_keys);
  }
  catch (const nlohmann::json::exception &e)
  {
    throw DeckError(path + ": not valid JSON (" + std::string(e.what()) + "): expected a " + what);
  }
}

double usable_memory_bytes()
{
  const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGE_SIZE);
  double bytes = pages > 0 && page > 0 ? double(pages) * double(page) : 0;
  std::ifstream limit("/sys/fs/cgroup/memory.max");
  double cgroup = 0;
  if (limit >> cgroup && cgroup > 0 && (bytes == 0 || cgroup < bytes))
    bytes = cgroup;
  return bytes;
}

void check_memory(double bytes, const std::string &what, const std::string &path, const std::string &key,
                  const std::string &value, const std::string &expected)
{
  const double usable = usable_memory_bytes();
  if (usable <= 0 || bytes <= usable)
    return;
  const auto gigabytes = [](double b)
  {
    char text[32];
    std::snprintf(text, sizeof text, "%.3g GB", b * 1e-9);
    return std::string(text);
  };
  fail_key(path, key, value,
           what + " would need about " + gigabytes(bytes) + " of memory, this machine has " + gigabytes(usable) + ": " +
             expected);
}

bool valid_utf8(const std::string &text)
{
  std::size_t k = 0;
  const std::size_t n = text.size();
  while (k < n)
  {
    const auto c = static_cast<unsigned char>(text[k]);
    std::size_t len = 0;
    std::uint32_t code = 0;
    if (c < 0x80)
    {
      ++k;
      continue;
    }
    if ((c & 0xE0) == 0xC0)
    {
      len = 2;
      code = c & 0x1F;
    }
    else if ((c & 0xF0) == 0xE0)
    {
      len = 3;
      code = c & 0x0F;
    }
    else if ((c & 0xF8) == 0xF0)
    {
      len = 4;
      code = c & 0x07;
    }
    else
      return false;
    if (k + len > n)
      return false;
    for (std::size_t j = 1; j < len; ++j)
    {
      const auto d = static_cast<unsigned char>(text[k + j]);
      if ((d & 0xC0) != 0x80)
        return false;
      code = (code << 6) | (d & 0x3F);
    }
    // Overlong forms, UTF-16 surrogates and code points past U+10FFFF are not UTF-8.
    const std::uint32_t least[] = {0, 0, 0x80, 0x800, 0x10000};
    if (code < least[len] || (code >= 0xD800 && code <= 0xDFFF) || code > 0x10FFFF)
      return false;
    k += len;
  }
  return true;
}

std::size_t control_character(const std::string &text)
{
  for (std::size_t k = 0; k < text.size(); ++k)
  {
    const auto c = static_cast<unsigned char>(text[k]);
    if (c < 0x20 || c == 0x7f)
      return k;
    if (c == 0xC2 && k + 1 < text.size() && static_cast<unsigned char>(text[k + 1]) >= 0x80 &&
        static_cast<unsigned char>(text[k + 1]) <= 0x9F)
      return k;
  }
  return std::string::npos;
}

std::string escaped(const std::string &text)
{
  std::string out;
  for (const char ch : text)
  {
    const auto c = static_cast<unsigned char>(ch);
    if (c >= 0x20 && c < 0x7F)
      out += ch;
    else
    {
      char hex[8];
      std::snprintf(hex, sizeof hex, "\\x%02X", c);
      out += hex;
    }
  }
  return out;
}
} // namespace demvv
