/* The avatar layer's only C++: urdfdom behind an extern "C" function that
 * copies the model into flat arrays and catches every exception. urdfdom
 * reports parse errors through console_bridge; while parsing, a capturing
 * output handler keeps the first error for the caller's message instead of
 * printing it (console_bridge's handler is process-global: parsing is not
 * meant to run concurrently with other console_bridge users). */
#include "urdf_parse.h"

#include <console_bridge/console.h>
#include <urdf_parser/urdf_parser.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <new>
#include <string>
#include <vector>

#include "skin_sim/ss_common.h"
#include "skin_sim/ssa_avatar.h"

namespace {

class CaptureHandler : public console_bridge::OutputHandler {
 public:
  std::string first_error;
  void log(const std::string &text, console_bridge::LogLevel level, const char *, int) override {
    if (level >= console_bridge::CONSOLE_BRIDGE_LOG_ERROR && first_error.empty()) first_error = text;
  }
};

char *dup_str(const std::string &s) {
  char *p = static_cast<char *>(std::malloc(s.size() + 1));
  if (!p) throw std::bad_alloc();
  std::memcpy(p, s.c_str(), s.size() + 1);
  return p;
}

template <typename T>
T *alloc_n(int n) {
  T *p = static_cast<T *>(std::calloc(n > 0 ? static_cast<size_t>(n) : 1, sizeof(T)));
  if (!p) throw std::bad_alloc();
  return p;
}

void put_pose(double *dst, const urdf::Pose &p) {
  dst[0] = p.position.x;
  dst[1] = p.position.y;
  dst[2] = p.position.z;
  dst[3] = p.rotation.x;
  dst[4] = p.rotation.y;
  dst[5] = p.rotation.z;
  dst[6] = p.rotation.w;
}

/* Puts handler h back as the current one. useOutputHandler also remembers
 * the handler it replaces as the "previous" one; setting h twice leaves
 * both slots at h, so no pointer to our stack-allocated capture survives. */
void restore_handler(console_bridge::OutputHandler *h) {
  console_bridge::useOutputHandler(h);
  console_bridge::useOutputHandler(h);
}

void set_err(char *err, int err_sz, const std::string &msg) {
  if (err && err_sz > 0) std::snprintf(err, static_cast<size_t>(err_sz), "%s", msg.c_str());
}

int fill(const urdf::ModelInterface &model, ssa_urdf_data *d) {
  std::vector<urdf::LinkSharedPtr> links;
  model.getLinks(links);
  std::map<std::string, int> link_index;
  d->robot_name = dup_str(model.getName());
  d->nlink = static_cast<int>(links.size());
  d->link_name = alloc_n<char *>(d->nlink);
  for (int i = 0; i < d->nlink; i++) {
    d->link_name[i] = dup_str(links[i]->name);
    link_index[links[i]->name] = i;
  }
  d->root_link = model.getRoot() ? link_index[model.getRoot()->name] : -1;

  const int nj = static_cast<int>(model.joints_.size());
  d->njoint = nj;
  d->joint_name = alloc_n<char *>(nj);
  d->joint_type = alloc_n<int>(nj);
  d->joint_parent = alloc_n<int>(nj);
  d->joint_child = alloc_n<int>(nj);
  d->joint_origin = alloc_n<double>(7 * nj);
  d->joint_axis = alloc_n<double>(3 * nj);
  d->joint_has_limits = alloc_n<int>(nj);
  d->joint_lower = alloc_n<double>(nj);
  d->joint_upper = alloc_n<double>(nj);
  d->joint_mimic = alloc_n<char *>(nj);
  d->joint_mimic_mult = alloc_n<double>(nj);
  d->joint_mimic_off = alloc_n<double>(nj);
  int j = 0;
  for (const auto &kv : model.joints_) {
    const urdf::Joint &jt = *kv.second;
    d->joint_name[j] = dup_str(jt.name);
    switch (jt.type) {
      case urdf::Joint::REVOLUTE: d->joint_type[j] = SSA_JOINT_REVOLUTE; break;
      case urdf::Joint::CONTINUOUS: d->joint_type[j] = SSA_JOINT_CONTINUOUS; break;
      case urdf::Joint::PRISMATIC: d->joint_type[j] = SSA_JOINT_PRISMATIC; break;
      case urdf::Joint::FIXED: d->joint_type[j] = SSA_JOINT_FIXED; break;
      default: d->joint_type[j] = SSA_JOINT_UNSUPPORTED; break;
    }
    auto pl = link_index.find(jt.parent_link_name);
    auto cl = link_index.find(jt.child_link_name);
    d->joint_parent[j] = pl == link_index.end() ? -1 : pl->second;
    d->joint_child[j] = cl == link_index.end() ? -1 : cl->second;
    put_pose(d->joint_origin + 7 * j, jt.parent_to_joint_origin_transform);
    d->joint_axis[3 * j + 0] = jt.axis.x;
    d->joint_axis[3 * j + 1] = jt.axis.y;
    d->joint_axis[3 * j + 2] = jt.axis.z;
    if (jt.limits && (jt.type == urdf::Joint::REVOLUTE || jt.type == urdf::Joint::PRISMATIC)) {
      d->joint_has_limits[j] = 1;
      d->joint_lower[j] = jt.limits->lower;
      d->joint_upper[j] = jt.limits->upper;
    }
    d->joint_mimic_mult[j] = 1.0;
    if (jt.mimic) {
      d->joint_mimic[j] = dup_str(jt.mimic->joint_name);
      d->joint_mimic_mult[j] = jt.mimic->multiplier;
      d->joint_mimic_off[j] = jt.mimic->offset;
    }
    j++;
  }

  int nv = 0;
  for (const auto &l : links) nv += static_cast<int>(l->visual_array.size());
  if (nv == 0) {
    for (const auto &l : links)
      if (l->visual) nv++;
  }
  d->nvisual = nv;
  d->visual_link = alloc_n<int>(nv);
  d->visual_geom = alloc_n<int>(nv);
  d->visual_uri = alloc_n<char *>(nv);
  d->visual_origin = alloc_n<double>(7 * nv);
  d->visual_scale = alloc_n<double>(3 * nv);
  d->visual_size = alloc_n<double>(3 * nv);
  int v = 0;
  for (int li = 0; li < d->nlink; li++) {
    std::vector<urdf::VisualSharedPtr> vis = links[li]->visual_array;
    if (vis.empty() && links[li]->visual) vis.push_back(links[li]->visual);
    for (const auto &vp : vis) {
      if (v >= nv) break;
      d->visual_link[v] = li;
      put_pose(d->visual_origin + 7 * v, vp->origin);
      d->visual_scale[3 * v + 0] = d->visual_scale[3 * v + 1] = d->visual_scale[3 * v + 2] = 1.0;
      const urdf::Geometry *g = vp->geometry.get();
      d->visual_geom[v] = SSA_GEOM_NONE;
      if (g) {
        switch (g->type) {
          case urdf::Geometry::MESH: {
            const auto *m = static_cast<const urdf::Mesh *>(g);
            d->visual_geom[v] = SSA_GEOM_MESH;
            d->visual_uri[v] = dup_str(m->filename);
            d->visual_scale[3 * v + 0] = m->scale.x;
            d->visual_scale[3 * v + 1] = m->scale.y;
            d->visual_scale[3 * v + 2] = m->scale.z;
            break;
          }
          case urdf::Geometry::BOX: {
            const auto *b = static_cast<const urdf::Box *>(g);
            d->visual_geom[v] = SSA_GEOM_BOX;
            d->visual_size[3 * v + 0] = b->dim.x;
            d->visual_size[3 * v + 1] = b->dim.y;
            d->visual_size[3 * v + 2] = b->dim.z;
            break;
          }
          case urdf::Geometry::SPHERE:
            d->visual_geom[v] = SSA_GEOM_SPHERE;
            d->visual_size[3 * v] = static_cast<const urdf::Sphere *>(g)->radius;
            break;
          case urdf::Geometry::CYLINDER:
            d->visual_geom[v] = SSA_GEOM_CYLINDER;
            d->visual_size[3 * v] = static_cast<const urdf::Cylinder *>(g)->radius;
            d->visual_size[3 * v + 1] = static_cast<const urdf::Cylinder *>(g)->length;
            break;
        }
      }
      v++;
    }
  }
  return SS_OK;
}

/* TinyXML 2.6.2 (urdfdom's XML reader) steps over a UTF-8 character by the
 * length its first byte announces without looking for the end of the text: a
 * text ending inside a character (e.g. '...xyz="0 0.17' then byte 0xCB) makes
 * it jump over the terminating NUL and parse on into whatever memory follows
 * (found by fuzz_urdf: an ASan heap-buffer-overflow in TiXmlBase::ReadName).
 * Such a text is refused here; and every text goes to TinyXML with NUL bytes
 * after its end, so that no such jump can leave it. Returns the offset of the
 * cut character, or -1. */
long cut_utf8_tail(const char *s, size_t n) {
  for (size_t k = 1; k <= 3 && k <= n; k++) {
    unsigned char c = static_cast<unsigned char>(s[n - k]);
    if (c < 0x80) return -1;  /* ASCII: no character is cut */
    if (c >= 0xC0) {          /* a first byte: 2, 3 or 4 bytes long */
      size_t len = c >= 0xF0 ? 4 : c >= 0xE0 ? 3 : 2;
      return len > k ? static_cast<long>(n - k) : -1;
    }
  }
  return -1;  /* continuation bytes only: TinyXML steps over them one by one */
}

}  // namespace

extern "C" int ssa_urdf_parse(const char *xml, ssa_urdf_data **out, char *err, int err_sz) {
  if (!out) return SS_E_ARG;
  *out = nullptr;
  if (!xml) {
    set_err(err, err_sz, "no URDF text");
    return SS_E_ARG;
  }
  ssa_urdf_data *d = static_cast<ssa_urdf_data *>(std::calloc(1, sizeof(ssa_urdf_data)));
  if (!d) return SS_E_NOMEM;
  CaptureHandler capture;
  console_bridge::OutputHandler *previous = console_bridge::getOutputHandler();
  int status = SS_OK;
  try {
    console_bridge::useOutputHandler(&capture);
    std::string text(xml);
    long cut = cut_utf8_tail(text.data(), text.size());
    if (cut >= 0) {
      restore_handler(previous);
      set_err(err, err_sz, "not a valid URDF: the text ends inside a UTF-8 character (byte " +
                               std::to_string(cut) + " of " + std::to_string(text.size()) + ")");
      ssa_urdf_data_free(d);
      return SS_E_IO;
    }
    text.append(8, '\0');  /* TinyXML reads up to the first NUL; these keep it inside */
    urdf::ModelInterfaceSharedPtr model = urdf::parseURDF(text);
    restore_handler(previous);
    if (!model) {
      std::string why = capture.first_error.empty() ? std::string("urdfdom could not parse it")
                                                    : capture.first_error;
      while (!why.empty() && (why.back() == '\n' || why.back() == '.' || why.back() == ' '))
        why.pop_back();
      set_err(err, err_sz, "not a valid URDF: " + why);
      status = SS_E_IO;
    } else if (!model->getRoot()) {
      set_err(err, err_sz, "the URDF has no root link");
      status = SS_E_IO;
    } else {
      status = fill(*model, d);
    }
    /* joints forming a cycle make a cycle of shared pointers (each link owns its
       children), which would never be freed: the links' child lists are no longer
       needed (the tables above are), so they are cleared */
    if (model)
      for (auto &kv : model->links_)
        if (kv.second) {
          kv.second->child_links.clear();
          kv.second->child_joints.clear();
        }
  } catch (const std::bad_alloc &) {
    restore_handler(previous);
    set_err(err, err_sz, "out of memory while reading the URDF");
    status = SS_E_NOMEM;
  } catch (const std::exception &e) {
    restore_handler(previous);
    set_err(err, err_sz, std::string("not a valid URDF: ") + e.what());
    status = SS_E_IO;
  } catch (...) {
    restore_handler(previous);
    set_err(err, err_sz, "not a valid URDF: unknown error in urdfdom");
    status = SS_E_IO;
  }
  if (status != SS_OK) {
    ssa_urdf_data_free(d);
    return status;
  }
  *out = d;
  return SS_OK;
}

static void free_strs(char **s, int n) {
  if (!s) return;
  for (int i = 0; i < n; i++) std::free(s[i]);
  std::free(s);
}

extern "C" void ssa_urdf_data_free(ssa_urdf_data *d) {
  if (!d) return;
  std::free(d->robot_name);
  free_strs(d->link_name, d->nlink);
  free_strs(d->joint_name, d->njoint);
  std::free(d->joint_type);
  std::free(d->joint_parent);
  std::free(d->joint_child);
  std::free(d->joint_origin);
  std::free(d->joint_axis);
  std::free(d->joint_has_limits);
  std::free(d->joint_lower);
  std::free(d->joint_upper);
  free_strs(d->joint_mimic, d->njoint);
  std::free(d->joint_mimic_mult);
  std::free(d->joint_mimic_off);
  std::free(d->visual_link);
  std::free(d->visual_geom);
  free_strs(d->visual_uri, d->nvisual);
  std::free(d->visual_origin);
  std::free(d->visual_scale);
  std::free(d->visual_size);
  std::free(d);
}
