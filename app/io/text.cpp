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
