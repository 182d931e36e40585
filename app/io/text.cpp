#include "app/io/text.h"

#include <cmath>
#include <cstdio>

namespace demvv
{
std::string format_number(double v, int significant)
{
  if (std::isinf(v))
    return v > 0 ? "inf" : "-inf";
  if (std::isnan(v))
    return "nan";
  char text[40];
  std::snprintf(text, sizeof text, "%.*g", significant, v);
  return text;
}

std::string one_line(std::string_view s, char replacement)
{
  std::string out(s);
  for (char &c : out)
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f)
      c = replacement;
  return out;
}

std::string readable_length(std::string_view s)
{
  // Words (runs without a blank) beyond 160 characters keep their first 100
  // and last 40: an echoed 100 kB value still names what it was.
  constexpr std::size_t long_word = 160, head = 100, tail = 40, most = 2000;
  // Cuts fall on UTF-8 character starts, never inside a character.
  const auto start_at = [](std::string_view t, std::size_t k)
  {
    while (k > 0 && k < t.size() && (static_cast<unsigned char>(t[k]) & 0xC0) == 0x80)
      --k;
    return k;
  };
  const auto cut = [&](std::string_view t, std::size_t keep_head, std::size_t keep_tail, const std::string &gap)
  {
    const std::size_t h = start_at(t, keep_head), e = start_at(t, t.size() - keep_tail);
    return std::string(t.substr(0, h)) + gap + std::string(t.substr(e));
  };
  std::string out;
  std::size_t i = 0;
  while (i < s.size())
  {
    const std::size_t blank = s.find(' ', i);
    const std::size_t end = blank == std::string_view::npos ? s.size() : blank;
    const std::string_view word = s.substr(i, end - i);
    if (word.size() > long_word)
      out += cut(word, head, tail, "...(" + std::to_string(word.size() - head - tail) + " characters left out)...");
    else
      out.append(word);
    if (end < s.size())
      out += ' ';
    i = end + 1;
  }
  // A message still too long keeps its start (the file and key) and its
  // end (what was expected).
  if (out.size() > most)
    out = cut(out, 1400, 400, " ...(" + std::to_string(out.size() - 1800) + " characters left out)... ");
  return out;
}

std::string trimmed(std::string_view s)
{
  const auto b = s.find_first_not_of(" \t\r\n");
  if (b == std::string_view::npos)
    return {};
  const auto e = s.find_last_not_of(" \t\r\n");
  return std::string(s.substr(b, e - b + 1));
}

void fail_key(const std::string &file, const std::string &key, const std::string &value, const std::string &expected)
{
  throw DeckError((file.empty() ? std::string("deck") : file) + ": key '" + key + "' has value '" + value +
                  "': " + expected);
}
} // namespace demvv
