#include "bxdf/presets.h"

namespace bxdf {

namespace {

// The seed's table gives one η and one k per metal, so the RGB values are grey.
Preset conductor(const std::string& name, double eta, double k) {
  Preset p;
  p.name = name;
  p.model = "microfacet";
  p.doc = "Polished " + name + " (seed: eta " + Value(eta).to_string() + ", k " +
          Value(k).to_string() + "), GGX alpha 0.1, conductor Fresnel";
  p.params.set("reflectance", RGBValue{1, 1, 1});
  p.params.set("distribution", "ggx");
  p.params.set("alpha_x", 0.1);
  p.params.set("alpha_y", 0.1);
  p.params.set("shadowing", "smith");
  p.params.set("fresnel", "conductor");
  p.params.set("eta", RGBValue{eta, eta, eta});
  p.params.set("k", RGBValue{k, k, k});
  return p;
}

// One Lafortune lobe with Cx = Cy = xy, as the published fits give it.
ParamSet lobe(RGBValue xy, RGBValue z, RGBValue n) {
  ParamSet l;
  l.set("cx", xy);
  l.set("cy", xy);
  l.set("cz", z);
  l.set("exponent", n);
  return l;
}

Preset lafortune(const std::string& name, const std::string& doc, RGBValue diffuse,
                 std::vector<ParamSet> lobes) {
  Preset p;
  p.name = name;
  p.model = "lafortune";
  p.doc = doc;
  p.params.set("diffuse", diffuse);
  p.params.set("lobes", std::move(lobes));
  return p;
}

RGBValue grey(double v) { return {v, v, v}; }

std::vector<Preset> build_presets() {
  std::vector<Preset> all = {
      conductor("gold", 0.370, 2.820),
      conductor("silver", 0.177, 3.638),
      conductor("copper", 0.617, 2.630),
      conductor("steel", 2.485, 3.433),
  };
  // Lafortune et al. 1997 three-lobe fits (as collected in pbrt v1; reference/models.md).
  all.push_back(lafortune(
      "clay", "Measured clay, Lafortune fit", {.383626, .260749, .274207},
      {lobe({-1.089701, -1.102701, -1.107603}, {-1.354682, -2.714801, -1.569866},
            {17.968505, 11.024489, 21.270282}),
       lobe({-.733381, -.793320, -.848206}, {.676108, .679314, .726031},
            {8.219745, 9.055139, 11.261951}),
       lobe({-1.010548, -1.012378, -1.011263}, {.910783, .885239, .892451},
            {152.912795, 141.937171, 201.046802})}));
  // Felt's third lobe: some copies give xy as -1.004921; we keep the table's +1.004921.
  all.push_back(lafortune("felt", "Measured grey felt, Lafortune fit", grey(.025865),
                          {lobe(grey(-.304075), grey(-.065992), grey(3.047892)),
                           lobe(grey(-.749561), grey(-1.167929), grey(6.931827)),
                           lobe(grey(1.004921), grey(-.205529), grey(94.117332))}));
  all.push_back(lafortune(
      "primer", "Measured primer, Lafortune fit", {.118230, .121218, .133209},
      {lobe({-.399286, -1.033473, -1.058104}, {.167504, .009545, -.068002},
            {2.466633, 7.637253, 8.117645}),
       lobe({-1.041861, -1.100108, -1.087779}, {.014375, -.198147, -.053605},
            {7.993722, 29.446268, 41.988990}),
       lobe({-1.098605, -.379883, -.449038}, {-.145110, .159127, .173224},
            {31.899719, 2.372852, 2.636161})}));
  all.push_back(lafortune(
      "skin", "Measured skin, Lafortune fit", {.428425, .301341, .331054},
      {lobe({-1.131747, -1.016939, -.966018}, {-1.209182, -1.462488, -1.222419},
            {6.421658, 3.699932, 3.524889}),
       lobe({-.546570, -.643533, -.638934}, {.380123, .410559, .437367},
            {3.685044, 4.266495, 4.539742}),
       lobe({-.998888, -1.020153, -1.027479}, {.857998, .703913, .573625},
            {64.208486, 63.919687, 43.809866})}));
  // Cornell's own published fit ("light blue housepaint"), not pbrt v1's transcription, whose
  // lobe-1 z is shifted by one channel and whose diffuse and lobe-2 n(R) differ.
  all.push_back(lafortune(
      "bluepaint", "Measured light-blue house paint, Cornell's Lafortune fit",
      {.3264, .3967, .7084},
      {lobe({.870567, .857255, .670982}, {.774290, .619944, .586674},
            {21.820103, 18.597755, 7.472717}),
       lobe({-.451218, -.406681, -.477976}, {.023123, .017625, .227295},
            {3.029342, 2.581499, 3.677653}),
       lobe({-1.031545, -1.029426, -1.026588}, {.706734, .696530, .687715},
            {66.899060, 63.767912, 57.489181})}));
  all.push_back(lafortune(
      "brushedmetal", "Measured brushed metal, Lafortune fit", grey(0),
      {lobe({-1.11854, -1.11845, -1.11999}, {1.01272, 1.01469, 1.01942},
            {15.8708, 15.6489, 15.4571}),
       lobe({-1.05334, -1.06409, -1.08378}, {.69541, .662178, .626672},
            {111.267, 88.9222, 65.2179}),
       lobe({-1.01684, -1.01635, -1.01529}, {1.00132, 1.00112, 1.00108},
            {180.181, 184.152, 195.773})}));
  return all;
}

}  // namespace

const std::vector<Preset>& presets() {
  static const std::vector<Preset> all = build_presets();
  return all;
}

const Preset* find_preset(const std::string& name) {
  for (const auto& p : presets())
    if (p.name == name) return &p;
  return nullptr;
}

std::string preset_names() {
  std::string s;
  for (const auto& p : presets()) s += (s.empty() ? "" : ", ") + p.name;
  return s;
}

BxDFPtr make_preset(const std::string& name) {
  const Preset* p = find_preset(name);
  if (!p) throw ParameterError("unknown preset '" + name + "'; known presets: " + preset_names());
  return make(p->model, p->params);
}

}  // namespace bxdf
