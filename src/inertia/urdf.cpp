// Repairing the inertias of a URDF robot description in place. tinyxml2 parses and checks the
// document; the repaired numbers are then written into the original text, so that everything
// else (comments, formatting, attribute quoting, other elements) is kept byte for byte, which a
// re-serialized DOM would not do.
#include <algorithm>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <vector>

#include <tinyxml2.h>

#include "io/read_file.hpp"
#include "spdfit/inertia_repair.hpp"
#include "spdfit/io.hpp"

namespace spdfit {

namespace {

using tinyxml2::XMLElement;

// A robot description is at most a few megabytes (meshes live in their own files).
constexpr std::size_t kMaxUrdfBytes = std::size_t{64} << 20;

constexpr const char* kInertiaAttributes[6] = {"ixx", "ixy", "ixz", "iyy", "iyz", "izz"};

// Where an attribute's value sits in the text: [begin, end).
struct AttributeSpan {
  std::string name;
  std::size_t begin = 0, end = 0;
};

// Every start tag <inertia ...> of the text in document order (comments, CDATA sections,
// processing instructions and the DOCTYPE skipped), with its attributes' value spans.
std::vector<std::vector<AttributeSpan>> inertia_start_tags(const std::string& text) {
  std::vector<std::vector<AttributeSpan>> tags;
  const std::size_t n = text.size();
  auto starts_with = [&](std::size_t i, const char* prefix) { return text.compare(i, std::char_traits<char>::length(prefix), prefix) == 0; };
  auto skip_past = [&](std::size_t from, const char* end) {
    const std::size_t at = text.find(end, from);
    return at == std::string::npos ? n : at + std::char_traits<char>::length(end);
  };
  auto is_space = [](char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; };
  std::size_t i = 0;
  while (i < n) {
    if (text[i] != '<') {
      ++i;
      continue;
    }
    if (starts_with(i, "<!--")) {
      i = skip_past(i + 4, "-->");
    } else if (starts_with(i, "<![CDATA[")) {
      i = skip_past(i + 9, "]]>");
    } else if (starts_with(i, "<?")) {
      i = skip_past(i + 2, "?>");
    } else if (starts_with(i, "<!")) {  // DOCTYPE, with an internal subset in brackets
      int depth = 0;
      for (++i; i < n; ++i) {
        if (text[i] == '[') ++depth;
        if (text[i] == ']') --depth;
        if (text[i] == '>' && depth <= 0) break;
      }
      ++i;
    } else {
      // A tag: its name, then attributes name = "value" up to '>' (quotes may hold '>').
      std::size_t j = i + 1;
      while (j < n && !is_space(text[j]) && text[j] != '>' && text[j] != '/') ++j;
      const bool wanted = text.compare(i + 1, j - i - 1, "inertia") == 0;
      std::vector<AttributeSpan> attributes;
      while (j < n && text[j] != '>') {
        if (is_space(text[j]) || text[j] == '/') {
          ++j;
          continue;
        }
        AttributeSpan a;
        const std::size_t name_begin = j;
        while (j < n && !is_space(text[j]) && text[j] != '=' && text[j] != '>') ++j;
        a.name = text.substr(name_begin, j - name_begin);
        while (j < n && is_space(text[j])) ++j;
        if (j < n && text[j] == '=') {
          ++j;
          while (j < n && is_space(text[j])) ++j;
          if (j < n && (text[j] == '"' || text[j] == '\'')) {
            const char quote = text[j];
            a.begin = j + 1;
            a.end = std::min(text.find(quote, a.begin), n);
            j = a.end + 1;
          }
        }
        attributes.push_back(std::move(a));
      }
      if (wanted) tags.push_back(std::move(attributes));
      i = j + 1;
    }
  }
  return tags;
}

// Every element named `name` under `root` (itself included), in document order.
void collect(XMLElement* root, const char* name, std::vector<XMLElement*>& out) {
  if (std::string(root->Name()) == name) out.push_back(root);
  for (XMLElement* child = root->FirstChildElement(); child; child = child->NextSiblingElement()) {
    collect(child, name, out);
  }
}

// The shortest decimal text that reads back as exactly `value`.
std::string shortest(double value) {
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  return std::string(buffer, result.ptr);
}

class LinkReader {
 public:
  LinkReader(const std::string& source, const std::string& link) : source_(source), link_(link) {}

  [[noreturn]] void fail(const XMLElement* at, const std::string& problem) const {
    throw io::DataError(source_, static_cast<std::size_t>(at->GetLineNum()), 0, "link \"" + link_ + "\": " + problem);
  }

  // The numbers of a whitespace-separated attribute value (count of them required).
  std::vector<double> numbers(const XMLElement* element, const char* attribute, std::size_t count,
                              bool required, std::vector<double> fallback = {}) const {
    const char* text = element->Attribute(attribute);
    const std::string where = std::string("<") + element->Name() + " " + attribute + ">";
    if (!text) {
      if (required) fail(element, where + " is missing");
      return fallback;
    }
    std::vector<double> out;
    const char* p = text;
    for (;;) {
      while (*p && std::isspace(static_cast<unsigned char>(*p))) ++p;
      if (!*p) break;
      char* end = nullptr;
      errno = 0;
      const double value = std::strtod(p, &end);
      if (end == p || (*end && !std::isspace(static_cast<unsigned char>(*end))) || !std::isfinite(value) ||
          errno == ERANGE) {
        fail(element, where + " must be " + (count == 1 ? "a finite number" : std::to_string(count) + " finite numbers") +
                          ", found \"" + text + "\"");
      }
      out.push_back(value);
      p = end;
    }
    if (out.size() != count) {
      fail(element, where + " must be " + std::to_string(count) + (count == 1 ? " number" : " numbers") +
                        ", found \"" + text + "\"");
    }
    return out;
  }

  const XMLElement* child(const XMLElement* parent, const char* name) const {
    const XMLElement* c = only(parent, name);
    if (!c) fail(parent, std::string("<") + parent->Name() + "> has no <" + name + ">");
    return c;
  }

  // The one <name> in `parent`, or none; a second is an error (which one is meant?), never ignored.
  const XMLElement* only(const XMLElement* parent, const char* name) const {
    const XMLElement* c = parent->FirstChildElement(name);
    if (c && c->NextSiblingElement(name)) {
      fail(c->NextSiblingElement(name), std::string("<") + parent->Name() + "> has a second <" + name +
                                            "> (the first is on line " + std::to_string(c->GetLineNum()) +
                                            "): keep the one that is meant");
    }
    return c;
  }

 private:
  const std::string& source_;
  const std::string& link_;
};

// tinyxml2's error as words: "not valid XML: mismatched element (XMLElement name=link)" for
// XML_ERROR_MISMATCHED_ELEMENT, without its numeric ErrorID (the line is the DataError's).
std::string xml_error(const tinyxml2::XMLDocument& doc) {
  std::string what = doc.ErrorName();
  for (const std::string prefix : {"XML_ERROR_", "XML_"}) {
    if (what.rfind(prefix, 0) == 0) {
      what.erase(0, prefix.size());
      break;
    }
  }
  std::transform(what.begin(), what.end(), what.begin(),
                 [](unsigned char c) { return c == '_' ? ' ' : static_cast<char>(std::tolower(c)); });
  std::string detail;
  if (const char* text = doc.ErrorStr()) {
    const std::string full = text;
    const std::size_t line = full.find("Line number=");
    const std::size_t colon = line == std::string::npos ? line : full.find(": ", line);
    if (colon != std::string::npos) detail = " (" + full.substr(colon + 2) + ")";
  }
  return "not valid XML: " + what + detail;
}

}  // namespace

std::size_t UrdfRepairResult::changed() const {
  return static_cast<std::size_t>(
      std::count_if(links.begin(), links.end(), [](const UrdfLinkRepair& l) { return l.result.changed; }));
}

UrdfRepairResult repair_urdf(const std::string& text, const std::string& source, const InertiaRepairOptions& options) {
  std::string error;
  if (!options.is_valid(&error)) throw std::invalid_argument(error);
  if (text.size() > kMaxUrdfBytes) {
    throw io::DataError(source, 0, 0,
                        "is " + std::to_string(text.size()) + " bytes long; at most " + std::to_string(kMaxUrdfBytes) +
                            " are accepted for a URDF file");
  }
  tinyxml2::XMLDocument doc;
  if (doc.Parse(text.data(), text.size()) != tinyxml2::XML_SUCCESS) {
    throw io::DataError(source, static_cast<std::size_t>(std::max(doc.ErrorLineNum(), 0)), 0, xml_error(doc));
  }
  XMLElement* robot = doc.RootElement();
  if (!robot || std::string(robot->Name()) != "robot") {
    throw io::DataError(source, robot ? static_cast<std::size_t>(robot->GetLineNum()) : 0, 0,
                        "a URDF file's root element must be <robot>, found <" +
                            std::string(robot ? robot->Name() : "") + ">");
  }
  std::vector<XMLElement*> inertia_elements;
  collect(robot, "inertia", inertia_elements);
  const std::vector<std::vector<AttributeSpan>> tags = inertia_start_tags(text);
  if (tags.size() != inertia_elements.size()) {
    throw io::DataError(source, 0, 0,
                        "found " + std::to_string(tags.size()) + " <inertia> start tags in the text but the XML parser found " +
                            std::to_string(inertia_elements.size()) + " <inertia> elements; cannot edit the file in place");
  }

  UrdfRepairResult out;
  struct Edit {
    std::size_t begin, end;
    std::string value;
  };
  std::vector<Edit> edits;
  for (XMLElement* link = robot->FirstChildElement("link"); link; link = link->NextSiblingElement("link")) {
    const std::string name = link->Attribute("name") ? link->Attribute("name") : "";
    const LinkReader in(source, name);
    const XMLElement* inertial = in.only(link, "inertial");
    if (!inertial) continue;
    RigidBodyInertia body;
    body.mass = in.numbers(in.child(inertial, "mass"), "value", 1, true)[0];
    if (const XMLElement* origin = in.only(inertial, "origin")) {
      const std::vector<double> xyz = in.numbers(origin, "xyz", 3, false, {0.0, 0.0, 0.0});
      body.center_of_mass = Eigen::Vector3d(xyz[0], xyz[1], xyz[2]);
    }
    const XMLElement* inertia = in.child(inertial, "inertia");
    double v[6];
    for (int k = 0; k < 6; ++k) v[k] = in.numbers(inertia, kInertiaAttributes[k], 1, true)[0];
    body.inertia << v[0], v[1], v[2], v[1], v[3], v[4], v[2], v[4], v[5];
    if (!is_well_formed(body, &error)) in.fail(inertial, error);

    UrdfLinkRepair repair;
    repair.link = name;
    repair.line = static_cast<std::size_t>(inertia->GetLineNum());
    repair.result = repair_inertia(body, options);
    if (repair.result.changed) {
      const auto index = static_cast<std::size_t>(
          std::find(inertia_elements.begin(), inertia_elements.end(), inertia) - inertia_elements.begin());
      const Eigen::Matrix3d& I = repair.result.repaired.inertia;
      const double repaired[6] = {I(0, 0), I(0, 1), I(0, 2), I(1, 1), I(1, 2), I(2, 2)};
      for (int k = 0; k < 6; ++k) {
        if (repaired[k] == v[k]) continue;  // an entry the repair left alone keeps its text
        const auto& attributes = tags[index];
        const auto span = std::find_if(attributes.begin(), attributes.end(),
                                       [&](const AttributeSpan& a) { return a.name == kInertiaAttributes[k]; });
        if (span == attributes.end() || span->end <= span->begin) {
          in.fail(inertia, std::string("cannot find attribute ") + kInertiaAttributes[k] + " of <inertia> in the text");
        }
        edits.push_back({span->begin, span->end, shortest(repaired[k])});
      }
    }
    out.links.push_back(std::move(repair));
  }

  // Apply from the end, so that the earlier spans stay where they were found.
  std::sort(edits.begin(), edits.end(), [](const Edit& a, const Edit& b) { return a.begin > b.begin; });
  out.text = text;
  for (const Edit& e : edits) out.text.replace(e.begin, e.end - e.begin, e.value);
  return out;
}

UrdfRepairResult repair_urdf_file(const std::string& path, const InertiaRepairOptions& options) {
  return repair_urdf(io::detail::read_file(path, kMaxUrdfBytes, "a URDF file"), path, options);
}

}  // namespace spdfit
