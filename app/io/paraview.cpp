#include "app/io/paraview.h"

#include "app/io/output.h"

#include <cstdio>
#include <sstream>

namespace demvv
{
namespace
{
void array(std::ostringstream &o, const char *name, int components, const std::vector<double> &values)
{
  o << "<DataArray type=\"Float64\" Name=\"" << name << "\" NumberOfComponents=\"" << components
    << "\" format=\"ascii\">\n";
  for (std::size_t k = 0; k < values.size(); ++k)
    o << values[k] << ((k + 1) % components == 0 ? "\n" : " ");
  o << "</DataArray>\n";
}

void vec_array(std::ostringstream &o, const char *name, const std::vector<dem::Vec3> &v)
{
  std::vector<double> flat;
  flat.reserve(3 * v.size());
  for (const auto &x : v)
    flat.insert(flat.end(), {x.x(), x.y(), x.z()});
  array(o, name, 3, flat);
}

std::string polydata(const std::vector<dem::Vec3> &points, const std::string &point_data,
                     const std::vector<std::pair<long, long>> &lines, const std::string &cell_data)
{
  std::ostringstream o;
  o.precision(10);
  o << "<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
    << "<PolyData>\n<Piece NumberOfPoints=\"" << points.size() << "\" NumberOfVerts=\"0\" NumberOfLines=\""
    << lines.size() << "\" NumberOfStrips=\"0\" NumberOfPolys=\"0\">\n";
  o << "<PointData>\n" << point_data << "</PointData>\n";
  o << "<CellData>\n" << cell_data << "</CellData>\n";
  o << "<Points>\n";
  vec_array(o, "Points", points);
  o << "</Points>\n<Lines>\n<DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n";
  for (const auto &l : lines)
    o << l.first << " " << l.second << "\n";
  o << "</DataArray>\n<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n";
  for (std::size_t k = 0; k < lines.size(); ++k)
    o << 2 * (k + 1) << "\n";
  o << "</DataArray>\n</Lines>\n</Piece>\n</PolyData>\n</VTKFile>\n";
  return o.str();
}

std::string collection(const std::string &stem, const std::vector<double> &times)
{
  std::ostringstream o;
  o.precision(12);
  o << "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n<Collection>\n";
  char name[64];
  for (std::size_t k = 0; k < times.size(); ++k)
  {
    std::snprintf(name, sizeof name, "%s_%05zu.vtp", stem.c_str(), k);
    o << "<DataSet timestep=\"" << times[k] << "\" file=\"" << name << "\"/>\n";
  }
  o << "</Collection>\n</VTKFile>\n";
  return o.str();
}
} // namespace

ParaviewWriter::ParaviewWriter(std::string dir) : dir_(std::move(dir)) { make_directories(dir_); }

nlohmann::json ParaviewWriter::state() const
{
  nlohmann::json broken = nlohmann::json::array();
  for (const BrokenBond &b : broken_)
    broken.push_back({b.point.x(), b.point.y(), b.point.z(), b.mode, b.time});
  return {{"frames", frame_}, {"times_s", times_}, {"broken", broken}};
}

void ParaviewWriter::restore(const nlohmann::json &state)
{
  frame_ = state.at("frames").get<int>();
  times_ = state.at("times_s").get<std::vector<double>>();
  broken_.clear();
  for (const nlohmann::json &b : state.at("broken"))
    broken_.push_back({dem::Vec3(b.at(0).get<double>(), b.at(1).get<double>(), b.at(2).get<double>()),
                       b.at(3).get<int>(), b.at(4).get<double>()});
}

void ParaviewWriter::add_breaks(const std::vector<dem::BondBreak> &breaks)
{
  for (const dem::BondBreak &b : breaks)
    broken_.push_back({b.point, static_cast<int>(b.mode), b.time});
}

void ParaviewWriter::write_frame(const dem::Simulation &sim, double time)
{
  const dem::ParticleStore &p = sim.particles();
  char suffix[32];
  std::snprintf(suffix, sizeof suffix, "_%05d.vtp", frame_);

  std::vector<double> id(p.size());
  for (dem::Index k = 0; k < p.size(); ++k)
    id[k] = ids_.empty() ? k : ids_[k];
  std::ostringstream pd;
  pd.precision(10);
  array(pd, "radius", 1, p.radius);
  array(pd, "id", 1, id);
  vec_array(pd, "velocity", p.velocity);
  vec_array(pd, "spin", p.spin);
  vec_array(pd, "force", p.force);
  write_atomically(dir_ + "/particles" + suffix, polydata(p.position, pd.str(), {}, ""));

  std::vector<std::pair<long, long>> lines;
  std::vector<double> fn, fs, state, bonded;
  for (const dem::Contact &c : sim.contacts().entries())
  {
    if (!c.state.touching())
      continue;
    lines.emplace_back(c.first, c.second);
    fn.push_back(c.state.normal_force);
    fs.push_back(c.state.shear_force.norm());
    state.push_back(c.state.normal_force >= 0 ? 1.0 : -1.0);
    bonded.push_back(c.bonded ? 1.0 : 0.0);
  }
  std::ostringstream cd;
  cd.precision(10);
  array(cd, "normal_force_n", 1, fn);
  array(cd, "shear_force_n", 1, fs);
  array(cd, "state", 1, state);
  array(cd, "bonded", 1, bonded);
  write_atomically(dir_ + "/contacts" + suffix, polydata(p.position, "", lines, cd.str()));

  std::vector<dem::Vec3> points;
  std::vector<double> mode, when;
  for (const BrokenBond &b : broken_)
  {
    points.push_back(b.point);
    mode.push_back(b.mode);
    when.push_back(b.time);
  }
  std::ostringstream bd;
  bd.precision(10);
  array(bd, "mode", 1, mode);
  array(bd, "time_s", 1, when);
  write_atomically(dir_ + "/breaks" + suffix, polydata(points, bd.str(), {}, ""));

  times_.push_back(time);
  ++frame_;
  for (const char *stem : {"particles", "contacts", "breaks"})
    write_atomically(dir_ + "/" + stem + ".pvd", collection(stem, times_));
}
} // namespace demvv
