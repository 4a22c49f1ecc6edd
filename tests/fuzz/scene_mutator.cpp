#include "scene_mutator.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "reeve/scene/scene.h"

extern "C" std::size_t LLVMFuzzerMutate(std::uint8_t* data, std::size_t size, std::size_t max_size);

namespace reeve::fuzz {
namespace {

using nlohmann::json;

constexpr int kMaxWalkDepth = 256;  // deeper documents get byte mutations only

// Nesting depth of JSON text, counted without parsing (brackets outside
// strings), so that no recursive walk below meets a deep document.
int depthOf(std::string_view text) {
  int depth = 0, deepest = 0;
  bool in_string = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (in_string) {
      if (c == '\\') ++i;
      else if (c == '"') in_string = false;
    } else if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      deepest = std::max(deepest, ++depth);
    } else if (c == ']' || c == '}') {
      --depth;
    }
  }
  return deepest;
}

void collectWords(const json& schema, std::vector<std::string>& words) {
  if (schema.is_object()) {
    for (const auto& [key, value] : schema.items()) {
      words.push_back(key);
      collectWords(value, words);
    }
  } else if (schema.is_array()) {
    for (const json& value : schema) collectWords(value, words);
  } else if (schema.is_string()) {
    words.push_back(schema.get<std::string>());
  }
}

// Property names and enum values of the scene schema, and a few more.
const std::vector<std::string>& words() {
  static const std::vector<std::string> all = [] {
    std::vector<std::string> w = {"", "x", "wheel", "box", "rope", "\xC3\xA9", std::string(300, 'a')};
    collectWords(json::parse(sceneSchemaJson()), w);
    std::sort(w.begin(), w.end());
    w.erase(std::unique(w.begin(), w.end()), w.end());
    return w;
  }();
  return all;
}

// Every value of the document, parents before children.
void collectNodes(json& value, std::vector<json*>& nodes) {
  nodes.push_back(&value);
  if (value.is_structured())
    for (json& child : value) collectNodes(child, nodes);
}

class Mutator {
 public:
  // Copies stop short of max_size bytes of JSON: 2,000 copies of a
  // megabyte subtree built gigabytes in the DOM before the size was
  // checked, and libFuzzer stopped on the memory limit (a finding of
  // issue 27's long run, in this mutator, not the loader).
  Mutator(unsigned seed, std::size_t max_size) : random_(seed), max_size_(max_size) {}

  void mutate(json& document) {
    std::vector<json*> nodes;
    collectNodes(document, nodes);
    json& node = *nodes[pick(nodes.size())];
    switch (pick(10)) {
      case 0: node = edgeNumber(node); break;
      case 1: node = word(); break;
      case 2: removeChild(node); break;
      case 3: copyChild(node, 1); break;
      case 4: copyChild(node, 1 + pick(pick(2) ? 10 : 2000)); break;  // grow: long arrays, big files
      case 5: node = json(*nodes[pick(nodes.size())]); break;  // a copy of another subtree (copied first)
      case 6: nest(node); break;
      case 7: node = pick(4) == 0 ? json() : pick(3) == 0 ? json(pick(2) == 1) : pick(2) ? json::object() : json::array(); break;
      case 8: addMember(node, *nodes[pick(nodes.size())]); break;
      default: swapChildren(node); break;
    }
  }

 private:
  std::size_t pick(std::size_t n) { return n == 0 ? 0 : std::uniform_int_distribution<std::size_t>(0, n - 1)(random_); }

  json word() { return words()[pick(words().size())]; }

  json edgeNumber(const json& old) {
    static const double kEdges[] = {0.0, -0.0, 1.0, -1.0, 2.0, 0.5, 1e-300, -1e-300, 1e-9, 1e9, 1e153, -1e153,
                                    1e154, 1e300, std::numeric_limits<double>::min(), 3.141592653589793,
                                    100000.0, 100001.0, 2147483647.0, 2147483648.0, 9007199254740993.0};
    const double x = old.is_number() ? old.get<double>() : 1.0;
    switch (pick(5)) {
      case 0: return kEdges[pick(std::size(kEdges))];
      case 1: return x * std::ldexp(1.0, static_cast<int>(pick(41)) - 20);
      case 2: return -x;
      case 3: return std::nextafter(x, pick(2) ? 1e308 : -1e308);
      default: return static_cast<std::int64_t>(pick(2) ? pick(8) : pick(200000)) - (pick(2) ? 1 : 0);
    }
  }

  void removeChild(json& node) {
    if (node.is_array() && !node.empty()) node.erase(pick(node.size()));
    else if (node.is_object() && !node.empty()) {
      const std::string key = std::next(node.begin(), static_cast<long>(pick(node.size()))).key();  // a copy
      node.erase(key);
    }
  }

  void copyChild(json& node, std::size_t copies) {
    if (!node.is_array() || node.empty()) return;
    const json item = node[pick(node.size())];
    if (copies > 1) copies = std::min(copies, max_size_ / std::max<std::size_t>(1, item.dump().size()));
    for (std::size_t k = 0; k < copies; ++k) node.insert(node.begin() + static_cast<long>(pick(node.size() + 1)), item);
  }

  void nest(json& node) {
    const std::size_t levels = 1 + pick(pick(4) ? 3 : 80);  // sometimes past the depth limit
    for (std::size_t k = 0; k < levels; ++k) node = pick(2) ? json::array({std::move(node)}) : json{{word().get<std::string>(), std::move(node)}};
  }

  void addMember(json& node, json value) {  // a copy: it may be an ancestor of node
    if (node.is_object()) node[word().get<std::string>()] = std::move(value);
    else if (node.is_array()) node.push_back(std::move(value));
  }

  void swapChildren(json& node) {
    if (node.is_array() && node.size() >= 2) std::swap(node[pick(node.size())], node[pick(node.size())]);
  }

  std::mt19937 random_;
  std::size_t max_size_;
};

}  // namespace

bool mutateScene(std::string& text, std::size_t max_size, unsigned seed) {
  if (depthOf(text) > kMaxWalkDepth) return false;
  json document = json::parse(text, nullptr, false);
  if (document.is_discarded()) return false;
  Mutator mutator(seed, max_size);
  const unsigned rounds = 1 + seed % 3;
  for (unsigned r = 0; r < rounds; ++r) mutator.mutate(document);
  std::string out = document.dump(seed % 7 == 0 ? 1 : -1);
  if (out.size() > max_size) return false;
  text = std::move(out);
  return true;
}

}  // namespace reeve::fuzz

// libFuzzer's hook: four mutations in five structural, the rest (and all
// of what is not JSON) byte-level.
extern "C" std::size_t LLVMFuzzerCustomMutator(std::uint8_t* data, std::size_t size, std::size_t max_size,
                                               unsigned int seed) {
  if (seed % 5 != 0) {
    std::string text(reinterpret_cast<const char*>(data), size);
    if (reeve::fuzz::mutateScene(text, max_size, seed)) {
      std::copy(text.begin(), text.end(), data);
      return text.size();
    }
  }
  return LLVMFuzzerMutate(data, size, max_size);
}
