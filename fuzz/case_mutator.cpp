// Mutations of case files (case_mutator.hpp).

#include "case_mutator.hpp"

#include <algorithm>
#include <array>
#include <string_view>
#include <utility>

namespace hfdda::fuzz {

namespace {

/// Values that sit on or beyond the edges of what the reader accepts: overflow,
/// underflow, not-a-number, integers past 32 bits, locale and C syntax.
constexpr std::array<std::string_view, 24> kNumbers{
    "1e308", "-1e308", "1e-300", "nan",   ".nan",   ".inf",      "-.inf",  "4294967297",
    "2147483647", "-2147483649", "-1",  "0",    "1,5",    "0x10",      "1e400",  "-0",
    "1e-320", "9223372036854775808", "0.1e1", "+1", "1e200", "1_000", "0o17", "1.5.2"};

/// YAML that changes the meaning of what follows, or text the reader must refuse.
constexpr std::array<std::string_view, 32> kSpecials{
    "---", "...", "!!str ", "!!float ", "&a ", "*a", "\"", "'", "\r", "\t", "{", "[", "}", "]",
    ": ", "- ", " #", "? ", "|", ">", "~", "\xff", "\xc3", "%YAML 1.2\n", "<<: ", "\\", "\n",
    ",", "\xef\xbb\xbf", "\xed\xa0\x80", std::string_view("\0", 1), "!"};

/// [begin, end) of every line, the newline included.
std::vector<std::pair<std::size_t, std::size_t>> lines_of(const std::string& text) {
  std::vector<std::pair<std::size_t, std::size_t>> lines;
  std::size_t start = 0;
  while (start < text.size()) {
    const std::size_t nl = text.find('\n', start);
    const std::size_t end = nl == std::string::npos ? text.size() : nl + 1;
    lines.emplace_back(start, end);
    start = end;
  }
  return lines;
}

bool word_char(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_';
}

bool digit(char c) { return c >= '0' && c <= '9'; }

/// [begin, end) of the numbers of `text`: runs of digits, signs, points and exponents
/// that start where a token may start and hold a digit.
std::vector<std::pair<std::size_t, std::size_t>> numbers_of(const std::string& text) {
  std::vector<std::pair<std::size_t, std::size_t>> found;
  std::size_t i = 0;
  while (i < text.size()) {
    const bool starts = (digit(text[i]) || text[i] == '-' || text[i] == '+' || text[i] == '.') &&
                        (i == 0 || !(word_char(text[i - 1]) || text[i - 1] == '.'));
    if (!starts) {
      ++i;
      continue;
    }
    std::size_t end = i + 1;
    bool has_digit = digit(text[i]);
    auto continues = [&](std::size_t k) {
      const char c = text[k];
      const bool exponent_sign = (c == '-' || c == '+') && (text[k - 1] == 'e' || text[k - 1] == 'E');
      return digit(c) || c == '.' || c == 'e' || c == 'E' || exponent_sign;
    };
    while (end < text.size() && continues(end)) {
      has_digit = has_digit || digit(text[end]);
      ++end;
    }
    if (has_digit) found.emplace_back(i, end);
    i = end;
  }
  return found;
}

/// [begin, end) of the words (identifiers) of `text`.
std::vector<std::pair<std::size_t, std::size_t>> words_of(const std::string& text) {
  std::vector<std::pair<std::size_t, std::size_t>> found;
  std::size_t i = 0;
  while (i < text.size()) {
    if (!word_char(text[i]) || digit(text[i])) {
      ++i;
      continue;
    }
    std::size_t end = i;
    while (end < text.size() && word_char(text[end])) ++end;
    found.emplace_back(i, end);
    i = end;
  }
  return found;
}

/// Where to insert: anywhere, at the start of a line, or where a line's value starts.
std::size_t insertion_point(const std::string& text, Rng& rng) {
  const auto lines = lines_of(text);
  if (lines.empty()) return 0;
  const auto [begin, end] = lines[rng.below(lines.size())];
  switch (rng.below(3)) {
    case 0: return rng.below(text.size() + 1);
    case 1: return begin;
    default: {
      const std::size_t colon = text.find(": ", begin);
      return colon != std::string::npos && colon < end ? colon + 2 : begin;
    }
  }
}

/// Brackets or maps inside each other, below and above the reader's limit of 16 levels.
std::string nesting(Rng& rng) {
  const std::size_t depth = 1 + rng.below(48);
  if (rng.chance(0.5)) return std::string(depth, '[') + "1" + std::string(depth, ']');
  std::string map;
  for (std::size_t i = 0; i < depth; ++i) map += "{k: ";
  return map + "1" + std::string(depth, '}');
}

}  // namespace

std::uint64_t Rng::next() {
  std::uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

Rng input_rng(std::uint64_t seed, std::uint64_t index) {
  Rng mix(seed ^ (index * 0xD1B54A32D192ED03ull));
  return Rng(mix.next());
}

CaseMutator::CaseMutator(std::vector<std::string> seeds) : seeds_(std::move(seeds)) {
  if (seeds_.empty()) seeds_.push_back("title: x\n");
  for (const auto& seed : seeds_)
    for (const auto& [b, e] : words_of(seed))
      if (e - b >= 2 && e - b <= 40) words_.push_back(seed.substr(b, e - b));
  std::sort(words_.begin(), words_.end());
  words_.erase(std::unique(words_.begin(), words_.end()), words_.end());
  if (words_.empty()) words_.push_back("title");
}

std::string CaseMutator::mutate_once(std::string& text, Rng& rng) const {
  auto lines = lines_of(text);
  switch (rng.below(13)) {
    case 0: {
      if (text.empty()) break;
      text[rng.below(text.size())] ^= static_cast<char>(1u << rng.below(8));
      return "flip_bit";
    }
    case 1: {
      const std::string_view bytes = " :-#[]{},'\"\n\r\t!&*|>?%@`\\0123456789.eE";
      const char c = rng.chance(0.7) ? bytes[rng.below(bytes.size())] : static_cast<char>(rng.below(256));
      text.insert(text.begin() + static_cast<std::ptrdiff_t>(rng.below(text.size() + 1)), c);
      return "insert_byte";
    }
    case 2: {
      if (text.empty()) break;
      const std::size_t at = rng.below(text.size());
      text.erase(at, 1 + rng.below(8));
      return "delete_bytes";
    }
    case 3: {
      if (lines.empty()) break;
      const auto [b, e] = lines[rng.below(lines.size())];
      text.erase(b, e - b);
      return "delete_line";
    }
    case 4: {
      if (lines.empty()) break;
      const auto [b, e] = lines[rng.below(lines.size())];
      std::string copy = text.substr(b, e - b);
      if (copy.empty() || copy.back() != '\n') copy += '\n';
      text.insert(b, copy);
      return "duplicate_line";
    }
    case 5: {
      if (lines.size() < 2) break;
      std::size_t i = rng.below(lines.size()), j = rng.below(lines.size());
      if (i == j) break;
      if (i > j) std::swap(i, j);
      std::string a = text.substr(lines[i].first, lines[i].second - lines[i].first);
      std::string b = text.substr(lines[j].first, lines[j].second - lines[j].first);
      if (a.empty() || a.back() != '\n') a += '\n';
      if (b.empty() || b.back() != '\n') b += '\n';
      text = text.substr(0, lines[i].first) + b + text.substr(lines[i].second, lines[j].first - lines[i].second) + a +
             text.substr(lines[j].second);
      return "swap_lines";
    }
    case 6: {
      // A run of lines of another seed, inserted at a line boundary or over a line run.
      const std::string& other = seeds_[rng.below(seeds_.size())];
      const auto other_lines = lines_of(other);
      if (other_lines.empty()) break;
      const std::size_t first = rng.below(other_lines.size());
      const std::size_t last = std::min(other_lines.size(), first + 1 + rng.below(6)) - 1;
      std::string piece = other.substr(other_lines[first].first, other_lines[last].second - other_lines[first].first);
      if (piece.back() != '\n') piece += '\n';
      if (lines.empty()) {
        text = piece;
      } else {
        const std::size_t at = rng.below(lines.size());
        const std::size_t replaced = rng.chance(0.5) ? 0 : std::min(lines.size() - at, 1 + rng.below(4));
        const std::size_t end = replaced == 0 ? lines[at].first : lines[at + replaced - 1].second;
        text.replace(lines[at].first, end - lines[at].first, piece);
      }
      return "splice";
    }
    case 7: {
      const auto numbers = numbers_of(text);
      if (numbers.empty()) break;
      const auto [b, e] = numbers[rng.below(numbers.size())];
      text.replace(b, e - b, kNumbers[rng.below(kNumbers.size())]);
      return "extreme_number";
    }
    case 8: {
      text.insert(insertion_point(text, rng), kSpecials[rng.below(kSpecials.size())]);
      return "yaml_special";
    }
    case 9: {
      text.insert(insertion_point(text, rng), nesting(rng));
      return "deep_nesting";
    }
    case 10: {
      // A long key (the limit is 64 characters) or a long value: the reader clips what it
      // echoes.
      const std::size_t at = lines.empty() ? 0 : lines[rng.below(lines.size())].first;
      const std::string line = rng.chance(0.5) ? std::string(50 + rng.below(100), 'k') + ": 1\n"
                                               : "title: " + std::string(500 + rng.below(3000), 'v') + "\n";
      text.insert(at, line);
      return "long_token";
    }
    case 11: {
      const auto words = words_of(text);
      if (words.empty()) break;
      const auto [b, e] = words[rng.below(words.size())];
      text.replace(b, e - b, words_[rng.below(words_.size())]);
      return "replace_word";
    }
    default: {
      if (text.empty()) break;
      text.resize(rng.below(text.size()));
      return "truncate";
    }
  }
  // The chosen mutation did not apply (empty text, one line): flip a byte or add one.
  if (text.empty()) {
    text = "title: x\n";
    return "restart";
  }
  text[rng.below(text.size())] ^= 0x20;
  return "flip_case";
}

std::string CaseMutator::make_input(Rng& rng, std::vector<std::string>* applied) const {
  std::string text = seeds_[rng.below(seeds_.size())];
  // One mutation half of the time, more with decreasing chance: small changes get past
  // the first check, stacked ones reach odd corners.
  int count = 1;
  while (count < 8 && rng.chance(0.5)) ++count;
  for (int i = 0; i < count; ++i) {
    const std::string name = mutate_once(text, rng);
    if (applied) applied->push_back(name);
    if (text.size() > kMaxInputBytes) text.resize(kMaxInputBytes);
  }
  return text;
}

}  // namespace hfdda::fuzz
