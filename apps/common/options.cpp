#include "common/options.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>
#include <set>
#include <sstream>

#include <fmt/format.h>

#include "common/app_main.hpp"
#include "common/material_options.hpp"
#include "powderbed/bed/errors.hpp"
#include "powderbed/bed/input_file.hpp"
#include "powderbed/bed/io.hpp"

namespace {

namespace po = boost::program_options;

// A validation_error whose text names the option (Boost fills %canonical_option%: "--count" on
// the command line, "count" in a scene file), the value and what is accepted.
[[noreturn]] void refuse_value(const std::string& value, const std::string& what) {
  po::validation_error e(po::validation_error::invalid_option_value);
  e.m_error_template = fmt::format("%canonical_option%: '%value%' {}", what);
  e.set_substitute("value", value);
  throw e;
}

std::string trimmed(const std::string& s) {
  const auto b = s.find_first_not_of(" \t");
  if (b == std::string::npos) return "";
  const auto e = s.find_last_not_of(" \t");
  return s.substr(b, e - b + 1);
}

// A whole number in [lo, hi] written as digits or as an exact number in e-notation ("1e6").
template <class T>
T parse_whole(const std::string& text, long double lo, long double hi, const char* accepted) {
  const std::string s = trimmed(text);
  if (s.empty()) refuse_value(text, fmt::format("is empty (accepted: {})", accepted));
  if constexpr (std::is_unsigned_v<T>) {
    if (s[0] == '-') refuse_value(text, fmt::format("is negative (accepted: {})", accepted));
  }
  {
    T v{};
    const char* begin = s.data() + (s[0] == '+' ? 1 : 0);
    const auto res = std::from_chars(begin, s.data() + s.size(), v);
    if (res.ec == std::errc() && res.ptr == s.data() + s.size()) return v;
    if (res.ec == std::errc::result_out_of_range)
      refuse_value(text, fmt::format("is out of range (accepted: {})", accepted));
  }
  double d = 0;
  const auto res = std::from_chars(s.data() + (s[0] == '+' ? 1 : 0), s.data() + s.size(), d);
  if (res.ec != std::errc() || res.ptr != s.data() + s.size() || !std::isfinite(d))
    refuse_value(text, fmt::format("is not a whole number (accepted: {})", accepted));
  if (d != std::floor(d))
    refuse_value(text, fmt::format("is not a whole number (accepted: {})", accepted));
  if (static_cast<long double>(d) < lo || static_cast<long double>(d) > hi)
    refuse_value(text, fmt::format("is out of range (accepted: {})", accepted));
  return static_cast<T>(d);
}

}  // namespace

namespace boost {

void validate(boost::any& v, const std::vector<std::string>& xs, unsigned long*, int) {
  program_options::validators::check_first_occurrence(v);
  const std::string& s = program_options::validators::get_single_string(xs);
  v = boost::any(parse_whole<unsigned long>(
      s, 0, static_cast<long double>(std::numeric_limits<unsigned long>::max()),
      "a whole number from 0 to 18446744073709551615"));
}

void validate(boost::any& v, const std::vector<std::string>& xs, unsigned int*, int) {
  program_options::validators::check_first_occurrence(v);
  const std::string& s = program_options::validators::get_single_string(xs);
  v = boost::any(parse_whole<unsigned int>(s, 0, std::numeric_limits<unsigned int>::max(),
                                           "a whole number from 0 to 4294967295"));
}

void validate(boost::any& v, const std::vector<std::string>& xs, int*, int) {
  program_options::validators::check_first_occurrence(v);
  const std::string& s = program_options::validators::get_single_string(xs);
  v = boost::any(parse_whole<int>(s, std::numeric_limits<int>::min(),
                                  std::numeric_limits<int>::max(),
                                  "a whole number from -2147483648 to 2147483647"));
}

void validate(boost::any& v, const std::vector<std::string>& xs, double*, int) {
  program_options::validators::check_first_occurrence(v);
  const std::string& text = program_options::validators::get_single_string(xs);
  const std::string s = trimmed(text);
  double d = 0;
  const char* begin = s.data() + (!s.empty() && s[0] == '+' ? 1 : 0);
  const auto res = std::from_chars(begin, s.data() + s.size(), d);
  if (s.empty() || res.ec != std::errc() || res.ptr != s.data() + s.size())
    refuse_value(text, "is not a number (accepted: a finite number, e.g. 30e-6)");
  if (!std::isfinite(d)) refuse_value(text, "is not finite (accepted: a finite number)");
  v = boost::any(d);
}

}  // namespace boost

namespace powderbed::app {

namespace {

// A value after "key =": "quoted" (escapes \\ \" \n \r \t; then only a comment may follow)
// or plain text up to a '#' comment, trimmed. `where` prefixes errors ("<file>:<line>: ").
std::string scene_value(const std::string& text, const std::string& where) {
  const std::string s = trimmed(text);
  if (s.empty() || s.front() != '"') return trimmed(s.substr(0, s.find('#')));
  std::string value;
  std::size_t k = 1;
  for (; k < s.size() && s[k] != '"'; ++k) {
    if (s[k] != '\\') {
      value += s[k];
      continue;
    }
    const char e = ++k < s.size() ? s[k] : '\0';
    const auto known = std::string_view("\\\"nrt").find(e);
    if (e == '\0' || known == std::string_view::npos)
      throw InputError(fmt::format("{}{} has an unknown escape (accepted: \\\\ \\\" \\n \\r \\t "
                                   "inside quotes)", where, s));
    value += "\\\"\n\r\t"[known];
  }
  const std::string rest = k < s.size() ? trimmed(s.substr(k + 1)) : "";
  if (k >= s.size() || (!rest.empty() && rest.front() != '#'))
    throw InputError(fmt::format("{}{} (accepted: a quoted value \"...\" closed before the line "
                                 "ends, then only a # comment)", where, s));
  return value;
}

}  // namespace

// The scene file, parsed as Boost's INI syntax ([section] sets the prefix "section.", key =
// value, '#' starts a comment) but one line at a time, so that every error names the file and
// the line: "<file>:<line>: <what>". A value may be "quoted" (scene_value), as --print-config
// writes one holding '#', a quote, a line break or spaces at its ends.
void store_scene_file(const std::string& path, const po::options_description& desc,
                      po::variables_map& vm, const std::string& option) {
  bed::require_regular_file(path, option);  // a folder, a FIFO (would block), a device
  std::ifstream in(path);
  if (!in) throw InputError(fmt::format("{}: cannot open scene file '{}'", option, path));
  std::string line, prefix;
  std::size_t number = 0;
  po::parsed_options all(&desc);
  while (std::getline(in, line)) {
    ++number;
    const std::string where = fmt::format("{}:{}: ", path, number);
    if (!line.empty() && line.back() == '\r') line.pop_back();
    // A '#' before the first '=' starts a comment; after it, the value's reader decides (quotes).
    const auto hash = line.find('#');
    const auto eq = line.find('=') < hash ? line.find('=') : std::string::npos;
    const std::string raw_value = eq == std::string::npos ? "" : line.substr(eq + 1);
    line = trimmed(line.substr(0, std::min(eq, hash)));
    if (line.empty()) continue;
    if (line.front() == '[') {
      if (line.back() != ']')
        throw InputError(fmt::format("{}{} (accepted: [section])", where, bed::quoted_excerpt(line)));
      prefix = trimmed(line.substr(1, line.size() - 2));
      if (!prefix.empty()) prefix += '.';
      continue;
    }
    if (eq == std::string::npos)
      throw InputError(fmt::format("{}{} (accepted: key = value, [section] or # comment)", where,
                                   bed::quoted_excerpt(line)));
    const std::string key = prefix + line;
    const std::string value = scene_value(raw_value, where);
    if (key == "config")
      throw InputError(fmt::format("{}config inside a scene file (accepted: one --config)", where));
    const po::option_description* known = desc.find_nothrow(key, false);
    if (!known)
      throw InputError(
          fmt::format("{}unknown option {} (see --help for the options)", where, bed::quoted_excerpt(key)));
    po::option opt;
    opt.string_key = key;
    // A switch without a value (bedstat's voronoi) is on with an empty value, as --print-config
    // writes it, or "true", and left off with "false".
    const bool switch_only = known->semantic()->max_tokens() == 0;
    if (switch_only && value == "false") continue;
    if (switch_only && !value.empty() && value != "true")
      throw InputError(fmt::format("{}{} = '{}' (accepted: true or false)", where, key, value));
    if (!switch_only) opt.value.push_back(value);
    opt.original_tokens = {key, value};
    all.options.push_back(opt);
    // This line's value checked on its own (with the key's earlier lines, so that a key given
    // twice is refused at its second line, as Boost refuses it), so the error can name it.
    po::parsed_options same_key(&desc);
    for (const auto& o : all.options)
      if (o.string_key == key) same_key.options.push_back(o);
    try {
      po::variables_map scratch;
      po::store(same_key, scratch);
    } catch (const po::error& e) {
      throw InputError(fmt::format("{}{}", where, e.what()));
    }
  }
  // Stored in one go, after the command line (command-line values win), as Boost's own
  // parse_config_file stores them: lines of one multi-valued option add up.
  po::store(all, vm);
}

namespace {

// The conventions every program shares (README "The programs", docs/hardening.md), checked once here.
void check_common(const po::variables_map& vm) {
  if (vm.count("threads") && !vm["threads"].defaulted()) {
    const auto& v = vm["threads"].value();
    if (const int* t = boost::any_cast<int>(&v); t && (*t < 0 || *t > 4096)) {
      throw InputError(fmt::format(
          "--threads: {} is out of range (accepted: 0 to 4096; 0 = the idle cores)", *t));
    }
  }
}

}  // namespace

void add_common_options(po::options_description& desc) {
  desc.add_options()("help,h", "print this help and exit")("version", "print the version and exit")(
      "config", po::value<std::string>(),
      "scene file (INI; [section] key = value sets --section.key); the command line wins")(
      "json", "print one JSON summary object on stdout")(
      "print-config",
      "print the resolved options (command line, scene file, material file and defaults) as a "
      "scene file for --config, and exit");
}

void add_progress_option(po::options_description& desc) {
  desc.add_options()("progress", po::value<double>()->default_value(10.0),
                     "batch runs (stderr not a terminal): seconds between progress lines on "
                     "stderr (0 = none)");
}

double progress_interval(const po::variables_map& vm) {
  return option_in_range<double>(vm, "progress", 0.0, 1e9, "seconds; 0 = no progress lines");
}

bool parse_options(const char* app, const std::string& usage, po::options_description& desc,
                   const po::positional_options_description& positional, int argc, char** argv,
                   po::variables_map& vm) {
  po::store(po::command_line_parser(argc, argv).options(desc).positional(positional).run(), vm);
  std::set<std::string> typed;  // what the command line gave (a --material file's rule needs it)
  for (const auto& [key, value] : vm)
    if (!value.defaulted()) typed.insert(key);
  if (vm.count("help")) {
    scene_style_defaults(desc);
    std::cout << "usage: " << usage << "\n\n" << desc << '\n';
    return false;
  }
  if (vm.count("version")) {
    std::cout << (vm.count("json") ? version_json(app) : version_string(app)) << '\n';
    return false;
  }
  if (list_materials(vm)) return false;
  if (vm.count("config")) {
    // Stored after the command line, so command-line values win (first store wins).
    store_scene_file(vm["config"].as<std::string>(), desc, vm);
  }
  po::notify(vm);  // the options bound to fields (po::value<T>(&field)) fill them
  check_common(vm);
  // A --material file's values are stored after po::notify (they need the resolved options): the
  // fields those options are bound to get them here.
  std::set<std::string> from_material;
  for (const std::string& name : apply_material(app, vm, typed)) {
    desc.find(name, false).semantic()->notify(vm[name].value());
    from_material.insert(name);
  }
  if (vm.count("print-config")) {
    std::cout << "# " << version_string(app)
              << ": the resolved options (--config reads this back from any folder; defaults "
                 "and a material file's values commented out)\n"
              << print_config_text(desc, vm, from_material);
    return false;
  }
  return true;
}

std::vector<double> parse_number_list(const std::string& text, std::size_t min_count,
                                      std::size_t max_count, const std::string& option) {
  std::vector<double> values;
  std::stringstream in(text);
  std::string item;
  auto range = [&] {
    return min_count == max_count ? fmt::format("{}", min_count)
                                  : fmt::format("{} to {}", min_count, max_count);
  };
  while (std::getline(in, item, ',')) {
    try {
      std::size_t used = 0;
      const double v = std::stod(item, &used);
      if (used != item.size() || !std::isfinite(v)) throw std::invalid_argument(item);
      values.push_back(v);
    } catch (const std::exception&) {
      throw InputError(fmt::format(
          "{}: '{}' is not a comma-separated list of numbers ({} expected)", option, text,
          range()));
    }
  }
  if (values.size() < min_count || values.size() > max_count) {
    throw InputError(fmt::format("{}: '{}' has {} numbers (accepted: {})", option, text,
                                 values.size(), range()));
  }
  return values;
}

bed::Domain parse_domain_lengths(const std::string& text, const std::string& option) {
  return bed::box_of_lengths(parse_number_list(text, 2, 3, option), option.c_str());
}

bed::Domain parse_domain_bounds(const std::string& text, const std::string& option) {
  const auto b = parse_number_list(text, 6, 6, option);
  bed::Domain d;
  d.lower = {b[0], b[1], b[2]};
  d.upper = {b[3], b[4], b[5]};
  d.dimension = (b[2] == 0 && b[5] == 0) ? 2 : 3;
  d.validate(option.c_str());
  return d;
}

namespace {

// The options every scene leaves out: they say how to run, not what to run.
bool meta_option(const std::string& key) {
  return key == "config" || key == "json" || key == "help" || key == "version" ||
         key == "progress" || key == "print-config" || key == "list-materials";
}

// The items of a value: one for a scalar, each line of a multi-valued option (lines add up).
std::vector<std::string> value_items(const boost::any& v) {
  if (const auto* list = boost::any_cast<std::vector<std::string>>(&v)) return *list;
  return {value_text(v).value_or("")};
}

// The options whose value is a file or folder, written absolute by --print-config so that the
// scene works from any folder; the second list also resolves beside the --config scene file when
// not found from the working folder (material_file, build's stage scenes), as they are read.
constexpr const char* kPathOptions[] = {
    "bed", "in", "out", "fused-bed", "scan-path", "tool-forces", "trajectory", "deck-scene",
    "height-map", "feed"};
constexpr const char* kSceneRelativeOptions[] = {"material", "material.table", "spread", "sinter"};

bool listed(const std::string& key, const auto& list) {
  return std::find(std::begin(list), std::end(list), key) != std::end(list);
}

// `path` as an absolute path, found as the program finds it: from the working folder, else (for
// the scene-relative options) beside the --config file. A material name stays a name.
std::string absolute_path(const std::string& key, const std::string& path,
                          const po::variables_map& vm) {
  namespace fs = std::filesystem;
  const bool beside = listed(key, kSceneRelativeOptions);
  if (!beside && !listed(key, kPathOptions)) return path;
  if (path.empty() || fs::path(path).is_absolute()) return path;
  const bool material = key == "material" || key == "material.table";
  if (material && path.find('/') == std::string::npos && bed::extension_of(path) != ".csv")
    return path;  // a name of --list-materials
  std::error_code ec;
  fs::path found = fs::absolute(path, ec);
  if (beside && !fs::exists(path, ec) && vm.count("config")) {
    const fs::path there = fs::absolute(vm["config"].as<std::string>(), ec).parent_path() / path;
    if (fs::exists(there, ec)) found = there;
  }
  return found.lexically_normal().string();
}

// A value as a scene line holds it: "quoted" with escapes when it holds what the plain form
// would lose ('#', a line break, a leading quote, spaces at its ends), else as it is.
std::string scene_quoted(const std::string& value) {
  const bool plain = value.find_first_of("#\n\r") == std::string::npos &&
                     (value.empty() || (value.front() != '"' && value.front() != ' ' &&
                                        value.front() != '\t' && value.back() != ' ' &&
                                        value.back() != '\t'));
  if (plain) return value;
  std::string out = "\"";
  for (const char c : value) {
    if (c == '\\' || c == '"') out += {'\\', c};
    else if (c == '\n') out += "\\n";
    else if (c == '\r') out += "\\r";
    else if (c == '\t') out += "\\t";
    else out += c;
  }
  return out + '"';
}

}  // namespace

std::optional<std::string> value_text(const boost::any& v) {
  if (const auto* s = boost::any_cast<std::string>(&v)) return *s;
  if (const auto* d = boost::any_cast<double>(&v)) {
    char text[32];  // the shortest text that reads back to the same double
    const auto end = std::to_chars(text, text + sizeof text, *d).ptr;
    return std::string(text, end);
  }
  if (const auto* b = boost::any_cast<bool>(&v)) return *b ? "true" : "false";
  if (const auto* u = boost::any_cast<std::uint64_t>(&v)) return std::to_string(*u);
  if (const auto* z = boost::any_cast<std::size_t>(&v)) return std::to_string(*z);
  if (const auto* i = boost::any_cast<int>(&v)) return std::to_string(*i);
  if (const auto* w = boost::any_cast<unsigned>(&v)) return std::to_string(*w);
  return std::nullopt;
}

std::string scene_text(const po::variables_map& vm) {
  std::string out;
  for (const auto& [key, value] : vm) {
    if (meta_option(key)) continue;
    // A switch without a value (bedstat's voronoi) prints an empty value.
    for (const auto& item : value_items(value.value())) out += key + " = " + item + '\n';
  }
  return out;
}

std::string print_config_text(const po::options_description& desc, const po::variables_map& vm,
                              const std::set<std::string>& from_material) {
  std::string out;
  for (const auto& [key, value] : vm) {
    if (meta_option(key)) continue;
    const po::option_description* known = desc.find_nothrow(key, false);
    const bool switch_only = known && known->semantic()->max_tokens() == 0;
    // Defaults and a material file's values are shown, commented out: read back as given, they
    // would become given values (and a default given alone may be refused).
    const bool filled = from_material.count(key) > 0;
    const std::string mark = value.defaulted() || filled ? "# " : "";
    const std::string why = value.defaulted() ? "  (default)" : filled ? "  (from --material)" : "";
    for (std::string item : value_items(value.value())) {
      // A switch given is on, whether Boost holds it as "" (no value) or true (bool_switch);
      // bedstat's switch --spread is no path, build's --spread is.
      if (switch_only) item = item.empty() ? "true" : item;
      else item = absolute_path(key, item, vm);
      out += fmt::format("{}{} = {}{}\n", mark, key, scene_quoted(item), why);
    }
  }
  return out;
}

namespace {

// Boost writes a default by lexical_cast (5.3999999999999998e-05, 1 for true): restated as a
// scene file writes it. The description holds the semantic const; Boost's value<T>() made it.
template <class T>
void restate_default(const po::value_semantic* semantic) {
  const auto* typed = dynamic_cast<const po::typed_value<T>*>(semantic);
  boost::any v;
  if (!typed || !typed->apply_default(v)) return;
  const_cast<po::typed_value<T>*>(typed)->default_value(boost::any_cast<T>(v), *value_text(v));
}

}  // namespace

void scene_style_defaults(po::options_description& desc) {
  for (const auto& option : desc.options()) {
    restate_default<double>(option->semantic().get());
    restate_default<bool>(option->semantic().get());
  }
}

namespace {

namespace fs = std::filesystem;

// The folder a path names its file in ("." for a bare name).
std::string folder_of(const std::string& path) {
  const auto slash = path.find_last_of('/');
  if (slash == std::string::npos) return ".";
  return slash == 0 ? "/" : path.substr(0, slash);
}


// The files a path stands for: itself and, for .h5, its XDMF sidecar.
std::vector<std::string> with_sidecar(const std::string& path) {
  std::vector<std::string> out{path};
  if (bed::extension_of(path) == ".h5") out.push_back(path.substr(0, path.size() - 3) + ".xmf");
  return out;
}

// Whether a and b name the same file (the same inode when both exist, else the same
// normalised absolute path).
bool same_file(const std::string& a, const std::string& b) {
  std::error_code ec;
  if (fs::exists(a, ec) && fs::exists(b, ec)) return fs::equivalent(a, b, ec);
  return fs::weakly_canonical(fs::absolute(a, ec), ec) == fs::weakly_canonical(fs::absolute(b, ec), ec);
}

}  // namespace

void check_paths(const std::vector<PathArg>& inputs, const std::vector<PathArg>& outputs) {
  for (const auto& in : inputs) {
    struct stat st {};
    if (::stat(in.path.c_str(), &st) != 0)
      throw InputError(fmt::format("{}: '{}' does not exist (accepted: a readable file)",
                                   in.option, in.path));
    bed::require_regular_file(in.path, in.option);  // a folder, a FIFO, a device
    if (::access(in.path.c_str(), R_OK) != 0)
      throw InputError(fmt::format("{}: '{}' is not readable (accepted: a readable file)",
                                   in.option, in.path));
  }
  for (std::size_t k = 0; k < outputs.size(); ++k) {
    const auto& out = outputs[k];
    if (out.path.empty())
      throw InputError(fmt::format("{}: empty path (accepted: a file name)", out.option));
    if (out.path.back() == '/')
      throw InputError(fmt::format("{}: '{}' names a folder (accepted: a file name)", out.option,
                                   out.path));
    for (const auto& file : with_sidecar(out.path)) {
      struct stat st {};
      if (::stat(file.c_str(), &st) == 0 && S_ISDIR(st.st_mode)) {
        const std::string sidecar =
            file == out.path ? "" : fmt::format(" (the sidecar of '{}')", out.path);
        throw InputError(fmt::format("{}: '{}' is a folder{} (accepted: a file name; nothing "
                                     "was written)", out.option, file, sidecar));
      }
    }
    const std::string folder = folder_of(out.path);
    struct stat st {};
    if (::stat(folder.c_str(), &st) != 0 || !S_ISDIR(st.st_mode)) {
      throw InputError(fmt::format(
          "{}: folder '{}' of '{}' does not exist (accepted: a file in an existing folder)",
          out.option, folder, out.path));
    }
    if (::access(folder.c_str(), W_OK | X_OK) != 0) {
      throw InputError(fmt::format(
          "{}: folder '{}' of '{}' is not writable (accepted: a file in a writable folder)",
          out.option, folder, out.path));
    }
    // The name, its sidecar (".h5" -> ".xmf": one more) and their temporaries (".tmp.<pid>")
    // must fit the file system's limit on a name.
    const std::size_t name = fs::path(out.path).filename().string().size(), room = 1 + 5 + 10;
    const long limit = ::pathconf(folder.c_str(), _PC_NAME_MAX);
    if (limit > 0 && name + room > static_cast<std::size_t>(limit)) {
      throw InputError(fmt::format("{}: the file name of '{}' is {} characters long (accepted: at "
                                   "most {}, the file system's {} less room for a temporary's suffix)",
                                   out.option, out.path, name, static_cast<std::size_t>(limit) - room, limit));
    }
    if (::access(out.path.c_str(), F_OK) == 0 && ::access(out.path.c_str(), W_OK) != 0) {
      // Replaced by rename, which needs only the folder; say so anyway: the user may mean it.
    }
    for (const auto& in : inputs) {
      for (const auto& o : with_sidecar(out.path)) {
        for (const auto& i : with_sidecar(in.path)) {
          if (same_file(o, i)) {
            throw InputError(fmt::format("{}: '{}' would overwrite the input {} '{}' (accepted: "
                                         "an output that is not an input)",
                                         out.option, out.path, in.option, in.path));
          }
        }
      }
    }
    for (std::size_t j = 0; j < k; ++j) {
      if (same_file(outputs[j].path, out.path)) {
        throw InputError(fmt::format("{}: '{}' is also {} (accepted: distinct outputs)",
                                     out.option, out.path, outputs[j].option));
      }
    }
  }
}

void check_extension(const PathArg& path, std::initializer_list<const char*> accepted,
                     const std::string& hint) {
  const std::string ext = bed::extension_of(path.path);
  std::string list;
  for (const char* a : accepted) {
    if (ext == a) return;
    if (!list.empty()) list += ", ";
    list += a;
  }
  throw InputError(fmt::format("{}: '{}' has extension '{}' (accepted: {}{}{})", path.option,
                               path.path, ext, list, hint.empty() ? "" : "; ", hint));
}

}  // namespace powderbed::app
