#include "bxdf/render/texture_group.h"

#include <cstring>

#include "texel_reads.h"

namespace bxdf::render {

std::shared_ptr<const TextureGroup> TextureGroup::make(const std::vector<const Texture*>& images) {
  if (images.size() < 2) return nullptr;
  auto group = std::make_shared<TextureGroup>();
  const TexelGrid& first = images[0]->texels();
  group->width_ = first.width;
  group->height_ = first.height;
  // Members in the caller's order; within a record floats first, then 4-byte texels, then
  // single bytes, so that every float stays 4-byte aligned.
  group->members_.resize(images.size());
  for (const TexelStorage storage :
       {TexelStorage::Floats, TexelStorage::Bytes, TexelStorage::GreyBytes}) {
    for (size_t k = 0; k < images.size(); ++k) {
      const TexelGrid& g = images[k]->texels();
      if (g.width != first.width || g.height != first.height) return nullptr;
      const TexelArray a = texel_array(g);
      if (a.storage != storage) continue;
      group->members_[k] = {storage, group->stride_, images[k]->settings()};
      group->stride_ += a.size;
    }
  }
  group->stride_ = (group->stride_ + 3) & ~size_t(3);
  const size_t texels = size_t(first.width) * size_t(first.height);
  if (group->stride_ * texels > kMaxBytes) return nullptr;
  group->data_.assign(group->stride_ * texels, 0);
  for (size_t k = 0; k < images.size(); ++k) {
    const TexelArray a = texel_array(images[k]->texels());
    unsigned char* target = group->data_.data() + group->members_[k].offset;
    for (size_t i = 0; i < texels; ++i)
      std::memcpy(target + i * group->stride_, a.base + i * a.size, a.size);
  }
  return group;
}

void TextureGroup::lookup(const TexelFootprint& f, const uint8_t* unassociate,
                          const int* outputs, Vec3* registers) const {
  if (f.inside && f.n == 2) {
    lookup_bilinear_inside(f, unassociate, outputs, registers);
    return;
  }
  for (size_t k = 0; k < members_.size(); ++k) {
    const Member& m = members_[k];
    const unsigned char* base = data_.data() + m.offset;
    // The records read as each storage reads its own texels (the same floats).
    const Float4 c = gather_stored(width_, height_, m.storage, base, stride_, f);
    store_node_outputs(image_node_convert(m.settings, c, unassociate[k] != 0),
                       registers + outputs[k]);
  }
}

// Linear inside the grid, the common case: the four records' addresses and the weights are
// worked out once for all members; each member's sum is gather()'s (bilinear_sum), the same floats.
void TextureGroup::lookup_bilinear_inside(const TexelFootprint& f, const uint8_t* unassociate,
                                          const int* outputs, Vec3* registers) const {
  const unsigned char* const data = data_.data();
  const unsigned char* const r00 = data + (f.rows[0] + size_t(f.xs[0])) * stride_;
  const unsigned char* const r10 = data + (f.rows[0] + size_t(f.xs[1])) * stride_;
  const unsigned char* const r01 = data + (f.rows[1] + size_t(f.xs[0])) * stride_;
  const unsigned char* const r11 = data + (f.rows[1] + size_t(f.xs[1])) * stride_;
  const BilinearWeights w = bilinear_weights(f);
  for (size_t k = 0; k < members_.size(); ++k) {
    const Member& m = members_[k];
    const size_t o = m.offset;
    auto sum = [&](Float4 (*decode)(const unsigned char*)) {
      return bilinear_sum(w, decode(r00 + o), decode(r10 + o), decode(r01 + o), decode(r11 + o));
    };
    Float4 c;
    switch (m.storage) {
      case TexelStorage::GreyBytes: c = sum(decode_grey_byte); break;
      case TexelStorage::Bytes: c = sum(decode_bytes); break;
      default: c = sum(decode_floats); break;
    }
    // image_node_convert changes nothing unless it unassociates or converts from sRGB.
    if (unassociate[k] || m.settings.colorspace == TextureColorspace::SRGB)
      c = image_node_convert(m.settings, c, unassociate[k] != 0);
    store_node_outputs(c, registers + outputs[k]);
  }
}

void TextureGroup::prefetch(const TexelFootprint& f) const {
  if (!f.inside) return;
  for (int j = 0; j < f.n; ++j) {
    const unsigned char* row = data_.data() + (f.rows[j] + size_t(f.xs[0])) * stride_;
    __builtin_prefetch(row);
    __builtin_prefetch(row + size_t(f.n) * stride_ - 1);  // the row's last texel of the footprint
  }
}

}  // namespace bxdf::render
