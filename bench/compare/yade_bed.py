# The bed of compare_codes.py in YADE: ViscElMat spheres (the linear
# spring-dashpot with Coulomb friction: k_n = k_t = 1000 N/m, restitution
# 0.5, friction 0.5, 2650 kg/m^3) in a box of six walls (aabbWalls, the lid
# above the bed), gravity, Cundall's local damping 0.7 in NewtonIntegrator,
# dt = 7e-6 s; YADE's own collider (InsertionSortCollider with its default
# Verlet distance). With "pfv", YADE's DEM-PFV pore flow (FlowEngine) as
# well: an excess pressure P_BOTTOM on the floor, zero on the lid, the
# other sides closed, water's viscosity.
# Run by compare_codes.py as
#   yade -n -x -j THREADS yade_bed.py BED_CSV SIDE STEPS RESULT_JSON [pfv P_BOTTOM]
import json
import math
import sys
import time

bed_csv, side, steps, result_json = sys.argv[1], float(sys.argv[2]), int(sys.argv[3]), sys.argv[4]
pfv = len(sys.argv) > 5 and sys.argv[5] == "pfv"

# ViscElMat takes k_n = 2 E r1 r2 / (r1 + r2) = E r for equal radii, and
# k_t = poisson x k_n: E = 1000 / 0.0005 = 2e6 Pa, poisson = 1 (the result
# reports a pair's k_n and k_t).
grain = O.materials.append(
    ViscElMat(young=2e6, poisson=1.0, en=0.5, et=0.5, frictionAngle=math.atan(0.5), density=2650.0))

centres = []
with open(bed_csv) as f:
    for line in f:
        if line.startswith("#") or line.startswith("x,"):
            continue
        centres.append(tuple(float(v) for v in line.split(",")))
top = max(z + r for x, y, z, r in centres)
# Walls first: FlowEngine takes bodies 0-5 as x_min, x_max, y_min, y_max,
# z_min, z_max.
walls = O.bodies.append(utils.aabbWalls([(0.0, 0.0, 0.0), (side, side, top + 1e-3)], thickness=0.0,
                                        material=grain))
floor = walls[4]
spheres = O.bodies.append([sphere((x, y, z), r, material=grain) for x, y, z, r in centres])
first_sphere = spheres[0]

engines = [
    ForceResetter(),
    InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Box_Aabb()]),
    InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Box_Sphere_ScGeom()],
                    [Ip2_ViscElMat_ViscElMat_ViscElPhys()],
                    [Law2_ScGeom_ViscElPhys_Basic()]),
]
if pfv:
    flow = FlowEngine(label="flow")
    flow.viscosity = 1e-3
    flow.bndCondIsPressure = [0, 0, 0, 0, 1, 1]
    flow.bndCondValue = [0, 0, 0, 0, float(sys.argv[6]), 0]
    flow.boundaryUseMaxMin = [0, 0, 0, 0, 0, 0]
    engines.append(flow)
engines.append(NewtonIntegrator(damping=0.7, gravity=(0.0, 0.0, -9.81)))
O.engines = engines
O.dt = 7e-6

start = time.time()
O.run(steps, True)
elapsed = time.time() - start

pair = None
contacts = 0
wall_contacts = 0
for i in O.interactions:
    if not i.isReal:
        continue
    if i.id1 >= first_sphere and i.id2 >= first_sphere:
        contacts += 1
        if pair is None:
            pair = i.phys
    else:
        wall_contacts += 1
masses = sum(O.bodies[k].state.mass for k in spheres)
result = {
    "code": "yade", "version": __import__("yade.config").config.version, "threads": O.numThreads,
    "steps": steps, "loop_seconds": elapsed, "particles": len(spheres), "grain_contacts": contacts,
    "wall_contacts": wall_contacts, "contact_kn": pair.kn if pair else None,
    "contact_ks": pair.ks if pair else None, "floor_force": abs(O.forces.f(floor)[2]), "weight": masses * 9.81,
    "kinetic_energy": utils.kineticEnergy(),
}
if pfv:
    result["pfv_inflow"] = flow.getBoundaryFlux(4)
    result["pfv_cells"] = flow.nCells()
with open(result_json, "w") as f:
    json.dump(result, f)
