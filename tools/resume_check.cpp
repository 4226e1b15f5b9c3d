#include "resume_check.hpp"

#include <algorithm>

#include <nlohmann/json.hpp>


namespace ssrcl::cli {
namespace {

std::string differs(const std::string& output, const std::string& what, const std::string& recorded,
                    const std::string& asked) {
  return output + ": exists with " + what + " " + recorded + ", but " + asked +
         " is asked now; give --overwrite to recompute it";
}

}  // namespace

std::string resumeMismatch(const std::string& output, const std::string& input, const OutputOptions& o,
                           const OutputRecord& asked) {
  const ExrDescription d = describeExr(output);
  const auto attribute = [&](const char* name) -> const std::string* {
    const auto it = d.stringAttributes.find(name);
    return it == d.stringAttributes.end() ? nullptr : &it->second;
  };
  const std::string* preset = attribute("ssrcl/preset");
  const std::string* settings = attribute("ssrcl/settings");
  if (!preset || !settings)
    return output + ": exists without ssrcl's record of how it was made (written by an older ssrcl or "
                    "another tool), so resuming cannot tell whether it matches; give --overwrite to recompute it";
  if (*preset != asked.preset) return differs(output, "preset", *preset, asked.preset);
  const std::string* form = attribute("ssrcl/output_form");  // absent before output forms: incident
  const std::string recordedForm = form ? *form : "incident";
  if (recordedForm != asked.outputForm) return differs(output, "output form", recordedForm, asked.outputForm);

  // The environment file is an input, not a setting: a different sky makes a different pass.
  const std::string* inputs = attribute("ssrcl/inputs");
  const nlohmann::json recordedInputs = inputs ? nlohmann::json::parse(*inputs, nullptr, false) : nlohmann::json();
  const std::string recordedEnvironment =
      recordedInputs.is_object() ? recordedInputs.value("environment", std::string()) : std::string();
  if (recordedEnvironment != asked.environment) {
    const auto named = [](const std::string& file) { return file.empty() ? std::string("none") : "'" + file + "'"; };
    return differs(output, "environment", named(recordedEnvironment), named(asked.environment));
  }

  // Views are inputs too (--view, --neighbours K). Neighbours take view slots in the order frames
  // were traced, so the lists are compared as sets.
  std::vector<std::string> recordedViews, askedViews = asked.views;
  if (recordedInputs.is_object() && recordedInputs.contains("views") && recordedInputs["views"].is_array())
    for (const auto& v : recordedInputs["views"])
      if (v.is_string()) recordedViews.push_back(v.get<std::string>());
  std::sort(recordedViews.begin(), recordedViews.end());
  std::sort(askedViews.begin(), askedViews.end());
  if (recordedViews != askedViews) {
    const auto listed = [](const std::vector<std::string>& files) {
      std::string out;
      for (const std::string& f : files) out += (out.empty() ? "'" : ", '") + f + "'";
      return out.empty() ? std::string("none") : out;
    };
    return differs(output, "views", listed(recordedViews), listed(askedViews));
  }

  // The frames a pass was blended with (--temporal K), in sequence order.
  std::vector<std::string> recordedTemporal;
  if (recordedInputs.is_object() && recordedInputs.contains("temporal") && recordedInputs["temporal"].is_array())
    for (const auto& v : recordedInputs["temporal"])
      if (v.is_string()) recordedTemporal.push_back(v.get<std::string>());
  if (recordedTemporal != asked.temporal)
    return differs(output, "temporal frames", std::to_string(recordedTemporal.size()) + " blended",
                   std::to_string(asked.temporal.size()));

  const nlohmann::ordered_json recorded = nlohmann::ordered_json::parse(*settings, nullptr, false);
  if (recorded.is_discarded() || !recorded.is_object())
    return output + ": its ssrcl/settings record is not a JSON object; give --overwrite to recompute it";
  const nlohmann::ordered_json now = nlohmann::ordered_json::parse(settingsJson(asked.settings));
  for (const auto& [key, value] : now.items()) {
    const auto it = recorded.find(key);
    if (it == recorded.end())
      return output + ": its ssrcl/settings record has no '" + key + "' (an older ssrcl); give --overwrite to recompute it";
    if (*it != value) return differs(output, key, it->dump(), value.dump());
  }

  const std::string layer = o.layerWritten();
  const std::string prefix = layer.empty() ? "" : layer + ".";
  const auto alpha = d.channelIsHalf.find(prefix + "A");
  if (alpha == d.channelIsHalf.end() || !d.channelIsHalf.count(prefix + "distance"))
    return output + ": exists without the channels " + prefix + "A and " + prefix +
           "distance of the asked output layer '" + layer + "'; give --overwrite to recompute it";
  if (alpha->second != o.half)
    return differs(output, "channel type", alpha->second ? "half" : "float", o.half ? "half" : "float");
  const std::string compression =
      !o.compression.empty() ? o.compression : o.append ? describeExr(input).compression : defaultExrCompression();
  if (d.compression != compression) return differs(output, "compression", d.compression, compression);
  return {};
}

}  // namespace ssrcl::cli
