#pragma once
/// \file vector_files.h
/// \brief Reading back what a PDF or SVG map holds, independently of cairo: the text a PDF
///        shows (its content streams inflated, each font's codes mapped to Unicode through the
///        font's ToUnicode CMap) and whether an SVG is well-formed XML. Enough PDF for what
///        cairo writes (uncompressed object table, fonts with ToUnicode), not a general reader.

#include <zlib.h>

#include <cctype>
#include <cstdint>
#include <fstream>
#include <iterator>
#include <map>
#include <regex>
#include <set>
#include <string>
#include <vector>

namespace pcl_ls3d_test {

/// The bytes of a file (empty when it cannot be read).
inline std::string
slurpBytes(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

/// The bytes of every stream of a PDF, inflated when FlateDecode, by object number.
inline std::map<int, std::string>
pdfStreams(const std::string& pdf)
{
  std::map<int, std::string> streams;
  const std::regex object(R"((\d+) 0 obj)");
  for (auto it = std::sregex_iterator(pdf.begin(), pdf.end(), object); it != std::sregex_iterator(); ++it) {
    const std::size_t body = static_cast<std::size_t>(it->position() + it->length());
    const std::size_t end = pdf.find("endobj", body), start = pdf.find("stream", body);
    if (start == std::string::npos || start > end)
      continue;
    std::size_t data = start + 6;
    data += pdf.compare(data, 2, "\r\n") == 0 ? 2 : 1;
    const std::string raw = pdf.substr(data, pdf.find("endstream", data) - data);
    std::string out = raw;
    if (pdf.substr(body, start - body).find("/FlateDecode") != std::string::npos) {
      out.clear();
      z_stream z{};
      inflateInit(&z);
      z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(raw.data()));
      z.avail_in = static_cast<uInt>(raw.size());
      char buffer[16384];
      int status = Z_OK;
      while (status == Z_OK) {
        z.next_out = reinterpret_cast<Bytef*>(buffer);
        z.avail_out = sizeof(buffer);
        status = inflate(&z, Z_NO_FLUSH);
        out.append(buffer, sizeof(buffer) - z.avail_out);
      }
      inflateEnd(&z);
    }
    streams[std::stoi((*it)[1])] = out;
  }
  return streams;
}

/// UTF-8 of one code point.
inline std::string
utf8Of(std::uint32_t cp)
{
  std::string s;
  if (cp < 0x80)
    s += static_cast<char>(cp);
  else if (cp < 0x800)
    s += {static_cast<char>(0xC0 | cp >> 6), static_cast<char>(0x80 | (cp & 0x3F))};
  else if (cp < 0x10000)
    s += {static_cast<char>(0xE0 | cp >> 12), static_cast<char>(0x80 | (cp >> 6 & 0x3F)),
          static_cast<char>(0x80 | (cp & 0x3F))};
  else
    s += {static_cast<char>(0xF0 | cp >> 18), static_cast<char>(0x80 | (cp >> 12 & 0x3F)),
          static_cast<char>(0x80 | (cp >> 6 & 0x3F)), static_cast<char>(0x80 | (cp & 0x3F))};
  return s;
}

/// A ToUnicode CMap: code → UTF-8 (bfchar entries and bfrange runs), and the code width.
struct CMap
{
  std::map<std::uint32_t, std::string> text;
  std::size_t hex_digits = 4;
};

inline CMap
parseCMap(const std::string& s)
{
  CMap m;
  std::smatch range;
  if (std::regex_search(s, range, std::regex(R"(begincodespacerange\s*<([0-9A-Fa-f]+)>)")))
    m.hex_digits = range[1].length();
  const auto hex = [](const std::string& h) {
    return static_cast<std::uint32_t>(std::stoul(h, nullptr, 16));
  };
  const std::regex one(R"(<([0-9A-Fa-f]+)>\s*<([0-9A-Fa-f]{4})>)");
  for (std::size_t at = 0; (at = s.find("beginbfchar", at)) != std::string::npos; ++at) {
    const std::string block = s.substr(at, s.find("endbfchar", at) - at);
    for (auto it = std::sregex_iterator(block.begin(), block.end(), one); it != std::sregex_iterator(); ++it)
      m.text[hex((*it)[1])] = utf8Of(hex((*it)[2]));
  }
  const std::regex run(R"(<([0-9A-Fa-f]+)>\s*<([0-9A-Fa-f]+)>\s*<([0-9A-Fa-f]{4})>)");
  for (std::size_t at = 0; (at = s.find("beginbfrange", at)) != std::string::npos; ++at) {
    const std::string block = s.substr(at, s.find("endbfrange", at) - at);
    for (auto it = std::sregex_iterator(block.begin(), block.end(), run); it != std::sregex_iterator(); ++it)
      for (std::uint32_t c = hex((*it)[1]); c <= hex((*it)[2]); ++c)
        m.text[c] = utf8Of(hex((*it)[3]) + c - hex((*it)[1]));
  }
  return m;
}

/// The bytes of the literal string starting at content[i] == '(' (escapes resolved, nested
/// parentheses kept); `i` moves past its closing parenthesis.
inline std::string
literalString(const std::string& content, std::size_t& i)
{
  std::string bytes;
  int depth = 0;
  for (++i; i < content.size(); ++i) {
    char c = content[i];
    if (c == '\\' && i + 1 < content.size()) {
      c = content[++i];
      if (c >= '0' && c <= '7') {  // up to three octal digits
        int v = 0;
        for (int k = 0; k < 3 && i < content.size() && content[i] >= '0' && content[i] <= '7'; ++k, ++i)
          v = 8 * v + (content[i] - '0');
        --i;
        c = static_cast<char>(v);
      } else if (c == 'n' || c == 'r' || c == 't')
        c = c == 'n' ? '\n' : c == 'r' ? '\r' : '\t';
      bytes += c;
      continue;
    }
    if (c == ')' && depth-- == 0)
      break;
    depth += c == '(';
    bytes += c;
  }
  ++i;
  return bytes;
}

/// Text of the string \a bytes in \a font (its codes are hex_digits / 2 bytes wide).
inline std::string
decoded(const std::string& bytes, const CMap* font)
{
  std::string text;
  const std::size_t width = font ? font->hex_digits / 2 : 1;
  for (std::size_t k = 0; font && k + width <= bytes.size(); k += width) {
    std::uint32_t code = 0;
    for (std::size_t b = 0; b < width; ++b)
      code = code << 8 | static_cast<unsigned char>(bytes[k + b]);
    text += font->text.count(code) ? font->text.at(code) : "?";
  }
  return text;
}

/// The text a PDF shows, one string per content stream: its strings (literal or hex) decoded
/// with the ToUnicode CMap of the font selected before them (Tf).
inline std::vector<std::string>
pdfText(const std::string& pdf)
{
  const std::map<int, std::string> streams = pdfStreams(pdf);
  std::map<std::string, CMap> fonts;  // resource name → its ToUnicode map
  const std::regex resource(R"(/(f-\d+-\d+) (\d+) 0 R)"), to_unicode(R"(/ToUnicode (\d+) 0 R)");
  for (auto it = std::sregex_iterator(pdf.begin(), pdf.end(), resource); it != std::sregex_iterator(); ++it) {
    const std::size_t at = pdf.find("\n" + std::string((*it)[2]) + " 0 obj");
    std::smatch m;
    const std::string body = at == std::string::npos ? "" : pdf.substr(at, pdf.find("endobj", at) - at);
    if (std::regex_search(body, m, to_unicode) && streams.count(std::stoi(m[1])))
      fonts[(*it)[1]] = parseCMap(streams.at(std::stoi(m[1])));
  }
  // Content streams: the pages' contents and form XObjects (what cairo draws into).
  std::set<int> contents;
  const std::regex page_contents(R"(/Contents (\d+) 0 R)"), form(R"(\n(\d+) 0 obj\s*<<[^>]*/Subtype /Form)");
  for (const std::regex* r : {&page_contents, &form})
    for (auto it = std::sregex_iterator(pdf.begin(), pdf.end(), *r); it != std::sregex_iterator(); ++it)
      contents.insert(std::stoi((*it)[1]));
  std::vector<std::string> texts;
  const std::regex select(R"(^/(f-\d+-\d+)\s+[\d.]+\s+Tf)");
  for (const auto& [number, content] : streams) {
    if (!contents.count(number))
      continue;
    std::string text;
    const CMap* font = nullptr;
    for (std::size_t i = 0; i < content.size();) {
      std::smatch m;
      if (content[i] == '/' &&
          std::regex_search(content.begin() + static_cast<std::ptrdiff_t>(i), content.end(), m, select)) {
        font = fonts.count(m[1]) ? &fonts.at(m[1]) : nullptr;
        i += static_cast<std::size_t>(m.length());
      } else if (content[i] == '(')
        text += decoded(literalString(content, i), font);
      else if (content[i] == '<' && i + 1 < content.size() && content[i + 1] != '<') {
        const std::size_t end = content.find('>', i);
        std::string bytes;
        for (std::size_t k = i + 1; k + 1 < end && std::isxdigit(static_cast<unsigned char>(content[k]));
             k += 2)
          bytes += static_cast<char>(std::stoi(content.substr(k, 2), nullptr, 16));
        text += decoded(bytes, font);
        i = end + 1;
      } else
        i += content[i] == '<' ? 2 : 1;
    }
    if (!text.empty())
      texts.push_back(text);
  }
  return texts;
}

/// True when \a xml is well-formed: one root element, every tag closed in order, attribute
/// values quoted, only the five named entities or numeric ones; `why` says what is wrong.
inline bool
wellFormedXml(const std::string& xml, std::string& why)
{
  std::vector<std::string> open;
  bool root_seen = false;
  const std::regex name(R"(^[A-Za-z_:][-A-Za-z0-9_:.]*)");
  const std::regex attribute(R"(^\s+[A-Za-z_:][-A-Za-z0-9_:.]*\s*=\s*("[^"<]*"|'[^'<]*'))");
  const std::regex entity(R"(^&(amp|lt|gt|quot|apos|#[0-9]+|#x[0-9A-Fa-f]+);)");
  for (std::size_t i = 0; i < xml.size();) {
    if (xml[i] == '&' && !std::regex_search(xml.begin() + static_cast<std::ptrdiff_t>(i), xml.end(), entity))
      return (why = "bad entity at " + std::to_string(i)).empty();
    if (xml[i] != '<') {
      if (open.empty() && !std::isspace(static_cast<unsigned char>(xml[i])))
        return (why = "text outside the root at " + std::to_string(i)).empty();
      ++i;
      continue;
    }
    const bool special = xml.compare(i, 2, "<?") == 0 || xml.compare(i, 4, "<!--") == 0;
    const std::size_t close = xml.find(special && xml[i + 1] == '!' ? "-->" : ">", i);
    if (close == std::string::npos)
      return (why = "unclosed tag at " + std::to_string(i)).empty();
    std::string tag = xml.substr(i + 1, close - i - 1);
    i = close + 1;
    if (special)
      continue;
    const bool end = !tag.empty() && tag[0] == '/', empty = !tag.empty() && tag.back() == '/';
    tag = tag.substr(end ? 1 : 0, tag.size() - (end ? 1 : 0) - (empty ? 1 : 0));
    std::smatch m;
    if (!std::regex_search(tag, m, name))
      return (why = "bad tag <" + tag + ">").empty();
    const std::string element = m[0];
    for (std::string rest = m.suffix();
         !rest.empty() && rest.find_first_not_of(" \t\r\n") != std::string::npos;) {
      std::smatch a;
      if (end || !std::regex_search(rest, a, attribute))
        return (why = "bad attributes in <" + tag + ">").empty();
      rest = a.suffix();
    }
    if (end) {
      if (open.empty() || open.back() != element)
        return (why = "</" + element + "> closes " + (open.empty() ? "nothing" : "<" + open.back() + ">"))
            .empty();
      open.pop_back();
    } else if (open.empty() && root_seen)
      return (why = "a second root <" + element + ">").empty();
    else if (!empty)
      open.push_back(element);
    root_seen = true;
  }
  if (!open.empty())
    return (why = "<" + open.back() + "> is never closed").empty();
  return root_seen || (why = "no root element").empty();
}

}  // namespace pcl_ls3d_test
