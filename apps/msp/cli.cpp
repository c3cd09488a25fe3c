#include "msp/cli.h"

#include <algorithm>
#include <cstdlib>
#include <sstream>

namespace msp {
namespace {

bool is_help(const std::string& a) { return a == "--help" || a == "-h"; }

/// "-1.5" is a value (a negative number), "-o" or "--json" an option.
bool looks_like_option(const std::string& a) {
  if (a.size() < 2 || a[0] != '-') return false;
  if (a[1] == '-') return a.size() > 2;
  char* end = nullptr;
  std::strtod(a.c_str(), &end);
  return *end != '\0';
}

const OptionSpec* find_option(const CommandSpec& spec, const std::string& name) {
  for (const auto& o : spec.options)
    if (o.name == name) return &o;
  return nullptr;
}

std::string option_usage(const OptionSpec& o) {
  std::string text = o.name == "output" ? "-o" : "--" + o.name;
  if (!o.value.empty()) text += " " + o.value;
  if (!o.required) text = "[" + text + "]";
  return o.repeatable ? text + "..." : text;
}

std::string see_help(const CommandSpec& spec) {
  return " (msp " + spec.name + " --help describes the command line)";
}

/// `text` broken into lines of at most `width` columns at spaces, joined by `separator`.
std::string wrap(const std::string& text, std::size_t width, const std::string& separator) {
  std::istringstream words(text);
  std::string out, line;
  for (std::string word; words >> word;) {
    if (!line.empty() && line.size() + 1 + word.size() > width) {
      out += line + separator;
      line.clear();
    }
    line += (line.empty() ? "" : " ") + word;
  }
  return out + line;
}

}  // namespace

std::string usage_text(const CommandSpec& spec, std::size_t width) {
  const std::string head = "msp " + spec.name;
  std::vector<std::string> items;
  for (const auto& p : spec.positionals) items.push_back(p.name);
  for (const auto& o : spec.options) items.push_back(option_usage(o));
  const std::string indent(head.size() + 1, ' ');
  std::string text = head, line = head;
  for (const auto& item : items) {
    if (line.size() > indent.size() && line.size() + 1 + item.size() > width) {
      text += "\n" + indent + item;
      line = indent + item;
    } else {
      text += " " + item;
      line += " " + item;
    }
  }
  return text + "\n";
}

std::string help_text(const CommandSpec& spec) {
  std::vector<std::pair<std::string, std::string>> rows;
  for (const auto& p : spec.positionals) rows.emplace_back(p.name, p.help);
  for (const auto& o : spec.options) {
    std::string left = o.name == "output" ? "-o, --output" : "--" + o.name;
    if (!o.value.empty()) left += " " + o.value;
    rows.emplace_back(left, o.help + (o.required ? " (required)" : "") +
                                (o.repeatable ? " (may be given more than once)" : ""));
  }
  rows.emplace_back("-h, --help", "print this help and exit");
  std::size_t column = 0;
  for (const auto& [left, right] : rows) column = std::max(column, left.size());
  column = std::min<std::size_t>(column, 28);
  const std::string indent(column + 4, ' ');
  std::ostringstream out;
  out << usage_text(spec) << "\n" << spec.summary << "\n\n";
  for (const auto& [left, right] : rows) {
    out << "  " << left;
    if (left.size() > column)
      out << "\n" << indent;
    else
      out << std::string(column - left.size() + 2, ' ');
    out << wrap(right, 100 - indent.size(), "\n" + indent) << "\n";
  }
  return out.str();
}

OptionSpec json_option() {
  return {"json", "", "print the result as one JSON object on stdout instead of text"};
}

OptionSpec quiet_option() { return {"quiet", "", "print no progress lines on stderr"}; }

OptionSpec metric_option(const std::string& fallback, bool intrinsic) {
  return {"metric",
          intrinsic ? "circle-packing|inversive-distance|combinatorial|intrinsic-delaunay"
                    : "circle-packing|inversive-distance|combinatorial",
          "the discrete conformal metric, used alone (without it: " + fallback + ")"};
}

OptionSpec radii_option() {
  return {"radii", "mean|min|least-squares", "how the circle radii are set from edge lengths"};
}

OptionSpec solver_option() {
  return {"solver", "auto|eigen-ldlt|eigen-llt|cholmod-supernodal|cholmod-simplicial",
          "the linear solver of the Newton steps (auto)"};
}

OptionSpec tolerance_option(const std::string& fallback) {
  return {"tolerance", "T", "stop the flow at max |K - target| below T (" + fallback + ")"};
}

OptionSpec singularity_option() {
  return {"singularity", "auto|VERTEX",
          "the extraordinary point: an interior vertex of the input, or auto (least area "
          "distortion)"};
}

Args::Args(int argc, char** argv, const CommandSpec& spec) : spec_(&spec) {
  for (int i = 0; i < argc; ++i)
    if (is_help(argv[i])) throw HelpRequested{&spec};
  for (int i = 0; i < argc; ++i) {
    const std::string a = argv[i];
    if (!looks_like_option(a)) {
      positionals_.push_back(a);
      continue;
    }
    std::string name, shown = a;
    std::optional<std::string> value;
    if (a == "-o") {
      name = "output";
    } else if (a.rfind("--", 0) == 0) {
      name = a.substr(2);
      if (const auto eq = name.find('='); eq != std::string::npos) {
        value = name.substr(eq + 1);
        name = name.substr(0, eq);
      }
      shown = "--" + name;
    } else {
      throw UsageError("unknown option " + a);
    }
    const OptionSpec* option = find_option(spec, name);
    if (!option) {
      throw UsageError(a == "-o" ? "option -o is not supported here" : "unknown option " + shown);
    }
    Occurrence occurrence{name, {}};
    const std::size_t arity = value_count(*option);
    if (arity == 0 && value) throw UsageError("option " + shown + " takes no value");
    if (value) occurrence.values.push_back(*value);
    while (occurrence.values.size() < arity) {
      if (i + 1 >= argc || looks_like_option(argv[i + 1])) {
        throw UsageError("option " + shown + " needs " +
                         (arity == 1 ? "a value" : std::to_string(arity) + " values") + " (" +
                         option->value + ")");
      }
      occurrence.values.push_back(argv[++i]);
    }
    if (occurrence.values.size() > arity)
      throw UsageError("option " + shown + " takes " + std::to_string(arity) + " values");
    std::string joined;
    for (const auto& v : occurrence.values) joined += (joined.empty() ? "" : " ") + v;
    options_[name] = joined;  // a repeated option: the last one
    occurrences_.push_back(std::move(occurrence));
  }
  for (const auto& o : spec.options) {
    if (o.required && !options_.count(o.name))
      throw UsageError(option_usage(o) + " is required" + see_help(spec));
  }
  const bool variadic = !spec.positionals.empty() && spec.positionals.back().name.size() > 3 &&
                       spec.positionals.back().name.compare(
                           spec.positionals.back().name.size() - 3, 3, "...") == 0;
  if (positionals_.size() > spec.positionals.size() && !variadic)
    throw UsageError("unexpected argument '" + positionals_[spec.positionals.size()] + "'" +
                     see_help(spec));
  if (positionals_.size() < spec.positionals.size())
    throw UsageError(spec.positionals[positionals_.size()].name + " is missing" + see_help(spec));
}

Args::Args(int argc, char** argv, std::initializer_list<std::string> flags) {
  for (int i = 0; i < argc; ++i) {
    std::string a = argv[i];
    if (a.size() > 2 && a.rfind("--", 0) == 0) {
      std::string name = a.substr(2);
      auto eq = name.find('=');
      if (eq != std::string::npos) {
        options_[name.substr(0, eq)] = name.substr(eq + 1);
      } else if (std::find(flags.begin(), flags.end(), name) != flags.end()) {
        options_[name] = "";
      } else if (i + 1 < argc) {
        options_[name] = argv[++i];
      } else {
        throw UsageError("option --" + name + " needs a value");
      }
    } else if (a == "-o" && i + 1 < argc) {
      options_["output"] = argv[++i];
    } else {
      positionals_.push_back(a);
    }
  }
}

void Args::check_declared(const std::string& name) const {
  if (spec_ && !find_option(*spec_, name))
    throw std::logic_error("msp " + spec_->name + " reads option --" + name +
                           ", which its CommandSpec does not declare");
}

std::size_t value_count(const OptionSpec& option) {
  std::istringstream words(option.value);
  std::size_t count = 0;
  for (std::string word; words >> word;) ++count;
  return count;
}

bool Args::has(const std::string& name) const {
  check_declared(name);
  return options_.count(name) > 0;
}

std::optional<std::string> Args::get(const std::string& name) const {
  check_declared(name);
  auto it = options_.find(name);
  if (it == options_.end()) return std::nullopt;
  return it->second;
}

std::vector<std::vector<std::string>> Args::get_all(const std::string& name) const {
  check_declared(name);
  std::vector<std::vector<std::string>> all;
  for (const auto& o : occurrences_)
    if (o.name == name) all.push_back(o.values);
  return all;
}

std::string Args::get_or(const std::string& name, const std::string& fallback) const {
  return get(name).value_or(fallback);
}

double Args::get_double(const std::string& name, double fallback) const {
  const auto v = get(name);
  return v ? parse_double(*v, "option --" + name) : fallback;
}

int Args::get_int(const std::string& name, int fallback) const {
  const auto v = get(name);
  return v ? parse_int(*v, "option --" + name) : fallback;
}

double parse_double(const std::string& text, const std::string& what) {
  try {
    size_t used = 0;
    const double x = std::stod(text, &used);
    if (used == text.size()) return x;
  } catch (const std::exception&) {
  }
  throw UsageError(what + " expects a number, got '" + text + "'");
}

int parse_int(const std::string& text, const std::string& what) {
  try {
    size_t used = 0;
    const int x = std::stoi(text, &used);
    if (used == text.size()) return x;
  } catch (const std::exception&) {
  }
  throw UsageError(what + " expects an integer, got '" + text + "'");
}

std::vector<int> parse_int_list(const std::string& text, const std::string& what) {
  std::vector<int> values;
  std::stringstream list(text);
  for (std::string item; std::getline(list, item, ',');) values.push_back(parse_int(item, what));
  if (values.empty()) throw UsageError(what + " expects integers separated by commas, got ''");
  return values;
}

void Args::require_known(const std::vector<std::string>& known) const {
  for (const auto& [name, value] : options_) {
    if (std::find(known.begin(), known.end(), name) == known.end()) {
      throw UsageError(name == "output" ? "option -o is not supported here"
                                        : "unknown option --" + name);
    }
  }
}

void Args::require_positionals(size_t count, const std::string& usage) const {
  if (positionals_.size() != count) throw UsageError("usage: " + usage);
}

}  // namespace msp
