"""The plane-strain P2 elasticity form alone (freefem/elasticity.idp).

- Patch test: a linear displacement (constant stress) imposed on a distorted mesh, by
  Dirichlet data on the whole boundary or by its exact traction on two sides, is
  reproduced to round-off, displacement and stress alike; also nearly incompressible.
- Manufactured solution: a smooth field with its body force converges at the P2 rates,
  3 in L2 and 2 in the H1 seminorm.
"""

import numpy as np
import pandas as pd
import pytest


@pytest.mark.parametrize("nu", [0.3, 0.49])
@pytest.mark.parametrize("traction", [0, 1], ids=["dirichlet", "traction"])
def test_patch_test_is_exact(run_freefem, tmp_path, nu, traction):
    output = tmp_path / f"patch-{nu}-{traction}.csv"
    run_freefem("elasticity_patch.edp", "-nu", nu, "-traction", traction, "-output", str(output))
    result = pd.read_csv(output).iloc[0]
    assert result.nodal_error < 1e-12 * result.field_size
    assert result.stress_error < 1e-11 * result.stress_size


def test_manufactured_solution_converges_at_the_p2_rates(run_freefem, tmp_path):
    errors = []
    for cells in (4, 8, 16, 32):
        output = tmp_path / f"manufactured-{cells}.csv"
        run_freefem("elasticity_manufactured.edp", "-cells", cells, "-output", str(output))
        errors.append(pd.read_csv(output).iloc[0][["l2_error", "h1_error"]].to_numpy(dtype=float))
    errors = np.array(errors)
    orders = np.log2(errors[:-1] / errors[1:])
    assert np.all(orders[1:, 0] >= 2.8), orders
    assert np.all(orders[1:, 1] >= 1.8), orders
