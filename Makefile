# Contact of elastic bodies with a thin partial coating: Robin DDM in FreeFEM + Python.
#   make fig3 fig4 fig5   the paper's figures (results/figN.png, .pdf, _data.csv) and its
#                         claims checked on their runs (results/claims.md)
#   make run     solve the default scene (shell model, h2 = b/8, E2 = E) into results/default
#   make test    run the tests (make test-fast: the everyday subset, under a minute)
#   make bench   speed against accuracy (results/bench.csv, results/speed_accuracy.png)
#   make stability  a sweep of 102 runs and maps of where each method converges
#   make discrete   a cylinder over a coating in patches, both models (results/discrete.png)
#   make adequacy   where each coating model is adequate, and model = "auto" checked
#                   on held-out plane and axisymmetric scenes (results/adequacy/)
#   make bond-shear the bond's peak shear against the elements through the coating
#                   (results/bond_shear_mesh.md)
#   make gallery    the engineers' scenes against the monolithic solve (results/gallery.md)
#   make iterations iterations per contact set against the mesh level (results/iterations.md)
#   make contrast   iterations per contact set across the indenter's modulus
#                   (results/indenter_contrast.md)
#   make stopping   converged runs against their tolerance, eps_u 1e-3 to 1e-6 on the
#                   gallery (results/stopping.md)
#   make two-level-robin  the fine loop's Robin parameter under two levels against the
#                   mesh level (results/two_level_robin.md)
#   make shell-edge each coating model's contact pressure against the penalty under a
#                   stiff indenter (results/shell_edge_penalty.md)
#   make line-contact  the field below a line contact, frictionless and sliding, against
#                   McEwen's closed form (results/line_contact_field.md)
#   make friction   iterations with friction against without (results/friction_iterations.md),
#                   the pressure's shift between unlike bodies (results/sliding_shift.md),
#                   partial slip against Cattaneo (results/partial_slip.md)
#   make sliding    a cylinder sliding over three patches: the bonds' peel and shear against
#                   its position, mu = 0, 0.2, 0.5 (results/sliding/)
#   make indentation  a ball on coated steel: indentation curves and stresses
#                   (results/indentation.md), and spheres against Hertz and a coated
#                   half-space reference (results/sphere_layered.md)
# Both install what they need first (FreeFEM from Debian, a pinned Python venv). Every
# study writes a report beside its tables (results/*.md: what it measured, computed).

PYTHON  := .venv/bin/python
APT_PACKAGES := freefem++ libfreefem++ libglu1-mesa libxcursor1 libxft2 libxinerama1
SUDO := $(shell [ "$$(id -u)" = 0 ] || echo sudo)

.PHONY: setup run test test-fast clean figures fig3 fig4 fig5 bench stability discrete adequacy bond-shear gallery iterations contrast stopping two-level-robin shell-edge indentation line-contact friction sliding
# A recipe that fails leaves no target behind that would look up to date (a sweep's
# runs.csv after an interrupted or failed run, say).
.DELETE_ON_ERROR:

# ---- The paper's figures: every scene listed once, in a sweep file ---------------------
# One command runs the sweep of the figures' scenes into results/figures/runs/ (runs.csv
# is written last; a rerun skips finished runs) and draws each figure as soon as the runs
# it needs are done. A form or solver source edited since runs.csv was written
# makes the runs stale: they are removed and solved again (so are the runs of a sweep
# that never wrote its table: nothing says which code solved them).
FIGURE_SWEEP := studies/sweeps/figures.toml
FIGURE_RUNS := results/figures/runs.csv
DRAWING_SOURCES := studies/figures.py studies/figure_scenes.py studies/figure_sweep.py
SOLVER_SOURCES := $(wildcard freefem/*.idp freefem/*.edp orchestrate/*.py orchestrate/*/*.py)

FIGURES := results/fig3.png results/fig4.png results/fig5.png
# the paper's claims checked on the figures' runs
CLAIMS := results/claims.md

figures: fig3 fig4 fig5
fig3 fig4 fig5: $(FIGURES) $(CLAIMS) ; @:

$(CLAIMS): $(FIGURE_RUNS) studies/claims.py studies/report.py | setup
	$(PYTHON) -m studies.claims results/figures

$(FIGURE_RUNS) $(FIGURES) &: $(FIGURE_SWEEP) $(SOLVER_SOURCES) $(DRAWING_SOURCES) | setup
	@if [ ! -f $(FIGURE_RUNS) ] || [ -n "$$(find $(SOLVER_SOURCES) -newer $(FIGURE_RUNS))" ]; \
	  then rm -rf results/figures/runs; fi
	$(PYTHON) -m studies.figure_sweep

# ---- A discrete coating (orchestrate/scenes/discrete.toml), both coating models ------
DISCRETE_RUNS := $(foreach m,shell elastic,results/discrete/$(m)/summary.json)
discrete: results/discrete.png
results/discrete.png: $(DISCRETE_RUNS) | setup
	$(PYTHON) -m orchestrate.plots.discrete_figure $(DISCRETE_RUNS) --out $@
results/discrete/%/summary.json: orchestrate/scenes/discrete.toml | setup
	$(PYTHON) -m orchestrate solve --quiet --overwrite --scene $< --model $* --out $(@D)

setup: .venv/.installed .freefem-installed
	@# the package byte-compiled (again where a source changed): an editable install is
	@# not, and where PYTHONDONTWRITEBYTECODE is set every process would compile it anew
	@$(PYTHON) -m compileall -q orchestrate studies >/dev/null

# FreeFEM and the X11/GL client libraries the gmsh wheel links against, from Debian.
.freefem-installed:
	@if dpkg -s $(APT_PACKAGES) >/dev/null 2>&1; then \
	  echo "FreeFEM and gmsh's libraries are installed"; \
	else \
	  $(SUDO) apt-get update -qq && \
	  DEBIAN_FRONTEND=noninteractive $(SUDO) apt-get install -y -qq $(APT_PACKAGES); \
	fi
	@touch $@

# The pinned dependencies, then orchestrate itself as an editable package
# (`import orchestrate` from any directory; pyproject.toml).
.venv/.installed: requirements.txt pyproject.toml
	python3 -m venv .venv
	$(PYTHON) -m pip install -q --upgrade pip
	$(PYTHON) -m pip install -q -r requirements.txt
	$(PYTHON) -m pip install -q --no-deps --no-build-isolation -e .
	@touch $@

run: setup
	$(PYTHON) -m orchestrate solve --overwrite --model shell --h2 0.125 --E2 1 --out results/default
	$(PYTHON) -m orchestrate plot results/default

# The tests run in TEST_JOBS processes (pytest-xdist), a test file to one process so that
# a module's shared runs are made once; every test checks only its own processes and
# folders, so they may share the machine.
TEST_JOBS ?= $(shell n=$$(nproc); [ $$n -gt 4 ] && n=4; echo $$n)
PYTEST := $(PYTHON) -m pytest -q -n $(TEST_JOBS) --dist loadfile

test: setup
	$(PYTEST) tests

# The everyday subset: the forms, the scene and its units, hostile input, the loop's
# pieces, one Robin-equals-monolithic check (under a minute); `make test` runs them all.
test-fast: setup
	$(PYTEST) -m "not slow" tests

# Speed against accuracy on the figure scenes (about 15 minutes; the fine references
# are computed once into results/reference/): results/bench.csv, speed_accuracy.png;
# the penalty's error against the mesh's at levels 1-3: results/penalty.csv; what workers
# kept from scene to scene save: results/session.csv, session_sweep.csv; each contact set
# solved directly against iterated and against the monolithic solve, mesh levels 1-3:
# results/direct.csv, direct_figure_scenes.csv.
bench: setup
	$(PYTHON) -m studies.bench
	$(PYTHON) -m studies.penalty
	$(PYTHON) -m studies.bench_session
	$(PYTHON) -m studies.bench_direct
	$(PYTHON) -m studies.bench_dask

# Where each method fails: a sweep of 102 runs (resumable), then its maps and charts
# (results/stability/). Errors use the fine references of `make bench` where they exist.
stability: setup
	$(PYTHON) -m orchestrate sweep studies/sweeps/stability.toml || [ $$? -eq 1 ]  # 1: some runs fail, as expected
	$(PYTHON) -m studies.stability results/stability

# The engineers' scenes (orchestrate/scenes/gallery/), each solved with default settings
# and by the monolithic solve of the same discrete problem: time to answer, iterations,
# and the answers' distance from the monolithic ones (results/gallery.csv, gallery.md).
gallery: setup
	$(PYTHON) -m studies.gallery

# Spherical indentation (axisymmetric scenes): a rigid ball on coated steel, its force
# stepped (results/indentation.csv, .md), and rigid spheres against Hertz and against an
# independent coated half-space solution (results/sphere_layered.csv, .md); the shells of
# revolution against the 2D coating as it thins (results/revolution_models.csv, .md).
indentation: setup
	$(PYTHON) -m studies.indentation
	$(PYTHON) -m studies.sphere_layered
	$(PYTHON) -m studies.revolution_models

# The stress field below a line contact against McEwen's closed form (the references of
# the frictional scenes: studies/line_contact_stresses.py): results/line_contact_field.md
line-contact: setup
	$(PYTHON) -m studies.line_contact_field

friction: setup
	$(PYTHON) -m studies.friction_iterations
	$(PYTHON) -m studies.sliding_shift
	$(PYTHON) -m studies.partial_slip

sliding: setup
	$(PYTHON) -m studies.sliding_patches

# Iterations per contact set of the gallery's scenes at mesh levels 1-3, the coatings
# inside the base's worker and exchanged across their bonds, the contacts' and bonds'
# sides unsplit, and two levels (results/iterations.md)
iterations: setup
	$(PYTHON) -m studies.iterations

# Iterations per contact set across the indenter's modulus, 1e-2 to 1e3 times the base's
# and rigid, split and unsplit, mesh levels 1-2 (results/indenter_contrast.md)
contrast: setup
	$(PYTHON) -m studies.indenter_contrast

# Every gallery scene at eps_u 1e-3, 1e-4, 1e-6 against a run to 1e-9, mesh levels 1-2:
# the largest error of a traction component against eps_u (results/stopping.md)
stopping: setup
	$(PYTHON) -m studies.stopping

# Two levels' fine Robin parameter fixed against growing with the band the coarse level
# leaves (the pads, the paper's scene, the discrete example; mesh levels 1-3;
# results/two_level_robin.md)
two-level-robin: setup
	$(PYTHON) -m studies.two_level_robin

# Each coating model's contact pressure (peak, its alternation from node to node) on the
# gallery's rigid and near-rigid cylinders at the default penalty and multiples of it
# (results/shell_edge_penalty.md)
shell-edge: setup
	$(PYTHON) -m studies.shell_edge_penalty

# The model error of each coating model over h2/a x E2/E (the paper's scene, a sphere on
# a coated cylinder) and the automatic choice on held-out scenes (about an hour and a
# half; finished scenes are kept in results/adequacy/*.csv, so an interrupted study
# resumes).
adequacy: setup
	$(PYTHON) -m studies.adequacy

# The bond's peak shear as the interface elements shrink against the coating's thickness,
# each coating model (results/bond_shear_mesh.md): the limit of the warning coarse_bond
bond-shear: setup
	$(PYTHON) -m studies.bond_shear_mesh

clean:
	rm -rf results/*/ .pytest_cache
