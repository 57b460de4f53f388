// Column selections: "acc1:acc6", "3:8", "1,3:5,F1" parsed, and resolved against a file's header.
#include "columns.hpp"
#include "io/row_selection.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <string_view>

#include "spdfit/format.hpp"

namespace spdfit::io {

namespace {

// One end of an item: a 1-based position (digits) or a header name.
struct End {
  bool is_position = false;
  std::size_t position = 0;
  std::string name;
  std::string text;  // as written
};

struct Item {
  End first, last;  // equal unless a range
  bool range = false;
};

std::string trimmed(std::string_view text) {
  std::size_t a = 0;
  std::size_t b = text.size();
  while (a < b && std::isspace(static_cast<unsigned char>(text[a]))) ++a;
  while (b > a && std::isspace(static_cast<unsigned char>(text[b - 1]))) --b;
  return std::string(text.substr(a, b - a));
}

// "`a_cols` 'acc1:acc9': "
std::string prefix(const ColumnSelection& s) { return "`" + s.option + "` '" + s.spec + "': "; }

[[noreturn]] void fail(const ColumnSelection& s, const std::string& problem) {
  throw ColumnSelectionError(prefix(s) + problem, s.option);
}

End parse_end(const ColumnSelection& s, const std::string& text, const std::string& item) {
  End end;
  end.text = text;
  if (text.empty()) fail(s, "'" + item + "' is a range without " + (item.front() == ':' ? "a start" : "an end"));
  const bool digits = std::all_of(text.begin(), text.end(), [](char c) { return std::isdigit(static_cast<unsigned char>(c)); });
  if (!digits) {
    end.name = text;
    return end;
  }
  end.is_position = true;
  if (text.size() > 9) fail(s, "column " + text + " does not exist");
  end.position = std::stoul(text);
  if (end.position == 0) {
    fail(s, "column positions count from 1 (digits are positions, even where the header's names are digits); "
            "there is no column 0");
  }
  return end;
}

std::vector<Item> parse(const ColumnSelection& s) {
  if (trimmed(s.spec).empty()) fail(s, "no columns given");
  std::vector<Item> items;
  std::size_t start = 0;
  while (start <= s.spec.size()) {
    std::size_t comma = s.spec.find(',', start);
    if (comma == std::string::npos) comma = s.spec.size();
    const std::string item = trimmed(std::string_view(s.spec).substr(start, comma - start));
    start = comma + 1;
    if (item.empty()) fail(s, "an empty item in the list (two commas in a row, or one at an end)");
    Item out;
    const std::size_t colon = item.find(':');
    if (colon == std::string::npos) {
      out.first = out.last = parse_end(s, item, item);
    } else {
      if (item.find(':', colon + 1) != std::string::npos) fail(s, "'" + item + "' has more than one ':'");
      out.range = true;
      out.first = parse_end(s, trimmed(item.substr(0, colon)), item);
      out.last = parse_end(s, trimmed(item.substr(colon + 1)), item);
      if (out.first.is_position && out.last.is_position && out.first.position > out.last.position) {
        fail(s, "the range " + item + " runs backwards (write " + out.last.text + ":" + out.first.text + ")");
      }
    }
    items.push_back(out);
  }
  return items;
}

std::string name_list(const std::vector<std::string>& names) {
  constexpr std::size_t kShown = 30;  // a wide file's header in full would bury the message
  std::string out;
  for (std::size_t i = 0; i < names.size() && i < kShown; ++i) {
    out += (i == 0 ? "" : ", ") + (names[i].empty() ? std::string("''") : names[i]);
  }
  if (names.size() > kShown) out += ", ... (" + std::to_string(names.size()) + " columns)";
  return out;
}

}  // namespace

void check_column_selection(const ColumnSelection& selection) { static_cast<void>(parse(selection)); }

std::string describe_columns(const std::vector<std::size_t>& positions, const std::vector<std::string>& names) {
  if (positions.empty()) return "no columns";
  const bool named = names.size() == positions.size();
  bool contiguous = positions.size() > 1;
  for (std::size_t i = 1; i < positions.size(); ++i) contiguous = contiguous && positions[i] == positions[i - 1] + 1;
  const std::string first = std::to_string(positions.front());
  const std::string last = std::to_string(positions.back());
  if (positions.size() == 1) return named ? "column " + names[0] + " (" + first + ")" : "column " + first;
  if (contiguous) {
    return named ? "columns " + names.front() + ".." + names.back() + " (" + first + "-" + last + ")"
                 : "columns " + first + "-" + last;
  }
  std::string numbers, labels;
  for (std::size_t i = 0; i < positions.size(); ++i) {
    numbers += (i == 0 ? "" : ", ") + std::to_string(positions[i]);
    if (named) labels += (i == 0 ? "" : ", ") + names[i];
  }
  return named ? "columns " + labels + " (" + numbers + ")" : "columns " + numbers;
}

std::vector<std::vector<std::size_t>> select_columns(const std::vector<ColumnSelection>& selections,
                                                     const std::vector<std::string>& names, const std::string& source) {
  return detail::one_based(detail::resolve_columns(selections, names, names.size(), true, source));
}

namespace detail {

std::vector<std::vector<std::size_t>> resolve_columns(const std::vector<ColumnSelection>& selections,
                                                      const std::vector<std::string>& names, std::size_t columns,
                                                      bool named, const std::string& source) {
  const std::string file = source == "-" ? std::string("standard input") : source;
  std::vector<std::vector<std::size_t>> out;
  std::map<std::size_t, std::size_t> owner;  // 0-based column -> the selection that took it
  const auto label = [&](std::size_t column) {
    std::string text = "column " + std::to_string(column + 1);
    if (column < names.size()) text += " (" + (names[column].empty() ? std::string("''") : names[column]) + ")";
    return text;
  };
  for (std::size_t k = 0; k < selections.size(); ++k) {
    const ColumnSelection& s = selections[k];
    const auto locate = [&](const End& end) -> std::size_t {
      if (end.is_position) {
        if (end.position > columns) {
          fail(s, "column " + std::to_string(end.position) + " is beyond the " + std::to_string(columns) +
                      " columns of " + file);
        }
        return end.position - 1;
      }
      if (names.empty()) {
        const std::string why = named ? file + " has no header row of column names"
                                      : file + " has no column names (.npy, .mat and .npz files have none)";
        fail(s, why + ": select its columns by 1-based position (1 to " + std::to_string(columns) + "), such as 2:7");
      }
      std::size_t found = names.size();
      for (std::size_t j = 0; j < names.size(); ++j) {
        if (names[j] != end.name) continue;
        if (found != names.size()) {
          fail(s, "the name " + end.name + " is in the header of " + file + " twice (columns " +
                      std::to_string(found + 1) + " and " + std::to_string(j + 1) + "): select by position");
        }
        found = j;
      }
      if (found == names.size()) {
        fail(s, "no column named " + end.name + " in " + file + "; its columns: " + name_list(names));
      }
      return found;
    };
    std::vector<std::size_t> chosen;
    for (const Item& item : parse(s)) {
      const std::size_t a = locate(item.first);
      const std::size_t b = item.range ? locate(item.last) : a;
      if (a > b) {
        fail(s, "the range " + item.first.text + ":" + item.last.text + " runs backwards: " + item.first.text +
                    " is column " + std::to_string(a + 1) + ", " + item.last.text + " column " + std::to_string(b + 1) +
                    " (write " + item.last.text + ":" + item.first.text + ")");
      }
      for (std::size_t c = a; c <= b; ++c) {
        const auto [it, fresh] = owner.emplace(c, k);
        if (!fresh) {
          if (it->second == k) fail(s, "selects " + label(c) + " twice");
          const ColumnSelection& other = selections[it->second];
          throw ColumnSelectionError("`" + other.option + "` '" + other.spec + "' and `" + s.option + "` '" + s.spec +
                                     "' both select " + label(c) + ": a column can be in one of them only",
                                     s.option);
        }
        chosen.push_back(c);
      }
    }
    out.push_back(std::move(chosen));
  }
  return out;
}

std::vector<std::size_t> concatenated(const std::vector<std::vector<std::size_t>>& chosen) {
  std::vector<std::size_t> out;
  for (const auto& c : chosen) out.insert(out.end(), c.begin(), c.end());
  return out;
}

std::vector<std::vector<std::size_t>> one_based(const std::vector<std::vector<std::size_t>>& chosen) {
  std::vector<std::vector<std::size_t>> out = chosen;
  for (auto& c : out) {
    for (std::size_t& p : c) ++p;
  }
  return out;
}

void select_table_columns(Table* table, const ReadOptions& options, const std::string& source) {
  if (options.columns.empty()) return;
  const auto chosen = resolve_columns(options.columns, {}, static_cast<std::size_t>(table->values.cols()), false, source);
  const std::vector<std::size_t> all = concatenated(chosen);
  Eigen::MatrixXd values(table->values.rows(), static_cast<Eigen::Index>(all.size()));
  for (std::size_t j = 0; j < all.size(); ++j) {
    values.col(static_cast<Eigen::Index>(j)) = table->values.col(static_cast<Eigen::Index>(all[j]));
  }
  table->values = std::move(values);
  table->column_names.clear();
  table->selected_columns = one_based(chosen);
}

}  // namespace detail

}  // namespace spdfit::io

namespace spdfit::io::detail {

namespace {

// One item of a row selection: first..last (1-based row numbers, or times with `by_time`; a
// missing end is open).
struct RowItem {
  std::string text;
  bool has_first = false, has_last = false;
  double first = 0.0, last = 0.0;
};

// How the numbers of a selection read: row numbers, times, or either (checked before `time_col` is
// known: the numbers' syntax only).
enum class RowUnits { Rows, Times, Either };

std::vector<RowItem> row_items(const std::string& spec, const std::string& option, RowUnits units) {
  const bool by_time = units != RowUnits::Rows;
  const std::string prefix = "`" + option + "` '" + spec + "': ";
  const auto fail = [&](const std::string& problem) {
    throw OptionError(prefix + problem, Code::OptionValue, option);
  };
  const auto trim = [](std::string_view text) {
    std::size_t a = 0, b = text.size();
    while (a < b && std::isspace(static_cast<unsigned char>(text[a]))) ++a;
    while (b > a && std::isspace(static_cast<unsigned char>(text[b - 1]))) --b;
    return std::string(text.substr(a, b - a));
  };
  if (trim(spec).empty()) fail("no rows given");
  std::vector<RowItem> items;
  std::size_t start = 0;
  while (start <= spec.size()) {
    std::size_t comma = spec.find(',', start);
    if (comma == std::string::npos) comma = spec.size();
    RowItem item;
    item.text = trim(std::string_view(spec).substr(start, comma - start));
    start = comma + 1;
    if (item.text.empty()) fail("an empty item in the list (two commas in a row, or one at an end)");
    const auto number = [&](const std::string& part, double* value) {
      const std::string t = trim(part);
      if (t.empty()) return false;
      if (by_time) {
        char* end = nullptr;
        *value = std::strtod(t.c_str(), &end);
        if (end != t.c_str() + t.size() || !std::isfinite(*value)) {
          fail("'" + t + "' in '" + item.text + "' is not " +
               (units == RowUnits::Times ? std::string("a time (a number in the units of `time_col`)")
                                         : std::string("a row number (nor a time, with `time_col`)")));
        }
        return true;
      }
      const bool digits =
          std::all_of(t.begin(), t.end(), [](char c) { return std::isdigit(static_cast<unsigned char>(c)); });
      if (!digits || t.size() > 15) {
        fail("'" + t + "' in '" + item.text + "' is not a row number (rows are numbered 1, 2, ... among the file's "
             "data rows, as the column selections number columns; give `time_col` for ranges of time)");
      }
      *value = static_cast<double>(std::stoull(t));
      if (*value == 0.0) fail("rows are numbered from 1: there is no row 0");
      return true;
    };
    const std::size_t colon = item.text.find(':');
    if (colon == std::string::npos) {
      number(item.text, &item.first);
      item.last = item.first;
      item.has_first = item.has_last = true;
    } else {
      if (item.text.find(':', colon + 1) != std::string::npos) fail("'" + item.text + "' has more than one ':'");
      item.has_first = number(item.text.substr(0, colon), &item.first);
      item.has_last = number(item.text.substr(colon + 1), &item.last);
      if (!item.has_first && !item.has_last) fail("the range '" + item.text + "' has neither a start nor an end");
      if (item.has_first && item.has_last && item.first > item.last) {
        fail("the range " + item.text + " runs backwards (write " + trim(item.text.substr(colon + 1)) + ":" +
             trim(item.text.substr(0, colon)) + ")");
      }
    }
    items.push_back(std::move(item));
  }
  return items;
}

}  // namespace

void check_row_selection(const std::string& spec, const std::string& option, bool by_time) {
  static_cast<void>(row_items(spec, option, by_time ? RowUnits::Either : RowUnits::Rows));
}

std::vector<Eigen::Index> selected_rows(const std::string& spec, const std::string& option, std::uint64_t rows,
                                        const std::string& source) {
  const std::vector<RowItem> items = row_items(spec, option, RowUnits::Rows);
  std::vector<bool> kept(rows, false);
  for (const RowItem& item : items) {
    const auto first = item.has_first ? static_cast<std::uint64_t>(item.first) : std::uint64_t{1};
    const auto last = item.has_last ? static_cast<std::uint64_t>(item.last) : rows;
    if (std::max(first, last) > rows) {
      throw DataError(source, 0, 0,
                      "`" + option + "` '" + spec + "': row " + std::to_string(std::max(first, last)) +
                          " is beyond the " + std::to_string(rows) + " data rows of " +
                          (source == "-" ? std::string("standard input") : source),
                      Code::DataShape);
    }
    for (std::uint64_t r = first; r <= last; ++r) kept[r - 1] = true;
  }
  std::vector<Eigen::Index> out;
  for (std::uint64_t r = 0; r < rows; ++r) {
    if (kept[r]) out.push_back(static_cast<Eigen::Index>(r));
  }
  return out;
}

std::vector<Eigen::Index> selected_times(const std::string& spec, const std::string& option,
                                         const Eigen::Ref<const Eigen::VectorXd>& time, const std::string& source) {
  const std::vector<RowItem> items = row_items(spec, option, RowUnits::Times);
  std::vector<Eigen::Index> out;
  for (Eigen::Index r = 0; r < time.size(); ++r) {
    const double t = time(r);
    for (const RowItem& item : items) {
      if ((!item.has_first || t >= item.first) && (!item.has_last || t <= item.last)) {
        out.push_back(r);
        break;
      }
    }
  }
  if (out.empty() && time.size() > 0) {
    throw DataError(source, 0, 0,
                    "`" + option + "` '" + spec + "': no row's time (`time_col`, from " +
                        format_number(time.minCoeff()) + " to " + format_number(time.maxCoeff()) +
                        ") is in these ranges",
                    Code::DataShape);
  }
  return out;
}

}  // namespace spdfit::io::detail
