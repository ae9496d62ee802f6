"""One material convention (issue 37 §8) and the modulus's unit check (§7).

A material ``(E, nu)`` is that of both bodies, ``A = 4 (1 - nu^2)/E``, in the
catalogue, at the command line and in Python; a case that is a rigid punch says
so and gets ``A = 2 (1 - nu^2)/E``. References: the two formulas typed in here,
the SIE (another method) for the contact, and the FE normal model run on the
block modulus of the one mapping. ``E`` outside the moduli of engineering
solids in MPa is refused by name wherever it is taken.
"""
from __future__ import annotations

import json
import re

import pytest

import threepart
from threepart import sie
from threepart.problem.catalogue import CASES_FILE, get_case, load_cases
from threepart.cli import main
from threepart.errors import InputError
from threepart.problem.material import E_RANGE, material_compliance, rigid_punch_modulus, similar_pair
from threepart.tolerances import tolerance

#: the catalogue's Ti-on-Ti flank and its material, as the issue typed it by hand
TI = get_case("fan_blade_flank")
E_TI, NU_TI = 115000.0, 0.32
#: the same contact by three entry points: the same formula, so equal to rounding
SAME = 1e-12
#: the issue's contact figures are printed to three decimals (mm)
PRINTED = 5e-4
#: ``threepart deck`` prints the model's A to 10 significant digits
PRINTED_A = 1e-9
#: the softest and the stiffest solid the modulus check must accept (MPa): nylon, diamond
NYLON_E, DIAMOND_E = 2000.0, 1.2e6


def _pair(E: float, nu: float) -> float:
    """Eq. (4) for two bodies of one material, typed in: ``2 (kappa + 1)/(4 mu)``."""
    return 4.0 * (1.0 - nu**2) / E


def _cli_contact(capsys: pytest.CaptureFixture[str], *material: str) -> tuple[float, float]:
    """``(-a, c)`` of ``threepart solve --json`` on the Ti flank typed by hand."""
    p = TI.punch
    argv = ["solve", "--R1", str(p.R1), "--R2", str(p.R2), "--b", str(p.b), "--P", str(TI.P),
            "--s", str(TI.s), *material, "--json"]
    assert main(argv) == 0
    doc = json.loads(capsys.readouterr().out)
    return -doc["a"], doc["c"]


def test_ti_on_ti_is_one_contact_in_the_catalogue_the_cli_and_python(capsys):
    assert TI.material == (E_TI, NU_TI) and TI.bodies == "similar pair"
    assert TI.A == pytest.approx(_pair(E_TI, NU_TI), rel=SAME)
    by_case = threepart.solve(TI.punch, TI.P, TI.s, A=TI.A)
    by_python = threepart.solve(TI.punch, TI.P, TI.s, A=material_compliance(E_TI, NU_TI))
    by_cli = _cli_contact(capsys, "--E", str(E_TI), "--nu", str(NU_TI))
    assert main(["solve", "--case", TI.name, "--json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    by_cli_case = (-doc["a"], doc["c"])
    W = by_case.a + by_case.c
    for got in ((-by_python.a, by_python.c), by_cli, by_cli_case):
        assert got == pytest.approx((-by_case.a, by_case.c), abs=SAME * W)
    # the independent reference: the SIE with A = 4(1 - nu^2)/E typed in
    ref = sie.solve_normal(TI.punch, TI.P, TI.s, A=_pair(E_TI, NU_TI))
    assert (-by_case.a, by_case.c) == pytest.approx((-ref.a, ref.c), abs=tolerance("sie", "a").limit * W)
    # the figures: [-1.850, 2.018] mm, not the rigid punch's [-1.538, 1.688]
    assert (-by_case.a, by_case.c) == pytest.approx((-1.850, 2.018), abs=PRINTED)


def test_the_ti_cases_with_friction_share_the_convention():
    for name in ("fan_blade_flank_bulk", "fan_blade_flight_cycle"):
        case = get_case(name)
        assert case.bodies == "similar pair" and case.A == pytest.approx(_pair(*case.material), rel=SAME)
    bulk = get_case("fan_blade_flank_bulk")
    normal = threepart.solve(bulk.punch, bulk.P, bulk.s, A=bulk.A)
    assert (-normal.a, normal.c) == pytest.approx((-1.850, 2.018), abs=PRINTED)


def test_a_case_marked_rigid_punch_gets_the_half_plane_compliance():
    sym = get_case("caseA_sym")
    assert sym.bodies == "rigid punch"
    assert sym.A == pytest.approx(2.0 * (1.0 - 0.3**2) / 210e3, rel=SAME)
    # every case with a material says which bodies it is; only the Ti-on-Ti ones are pairs
    pairs = {c.name for c in load_cases(None) if c.material is not None and c.bodies == "similar pair"}
    assert pairs == {"fan_blade_flank", "fan_blade_flank_bulk", "fan_blade_flight_cycle", "fan_blade_flank_wear"}


def _catalogue(tmp_path, **fields):
    data = json.loads(CASES_FILE.read_text(encoding="utf-8"))
    case = {k: v for k, v in data["cases"][0].items() if k != "bodies"}
    data["cases"] = [dict(case, **fields)]
    path = tmp_path / "cases.json"
    path.write_text(json.dumps(data))
    return path


def test_the_bodies_field_sets_the_compliance_and_nothing_guesses(tmp_path):
    mat = {"E": 4000.0, "nu": 0.0}
    assert load_cases(None, _catalogue(tmp_path, material=mat))[0].A == pytest.approx(1e-3, rel=SAME)
    rigid = load_cases(None, _catalogue(tmp_path, material=mat, bodies="rigid punch"))[0]
    assert rigid.A == pytest.approx(5e-4, rel=SAME)
    assert rigid.as_dict()["bodies"] == "rigid punch"
    with pytest.raises(ValueError, match=r"`bodies` = 'steel' must be one of"):
        load_cases(None, _catalogue(tmp_path, material=mat, bodies="steel"))


@pytest.mark.parametrize("E, unit", [(210e9, "Pa"), (2.1e8, "kPa"), (210.0, "GPa"), (70.0, "GPa")])
def test_a_modulus_outside_engineering_solids_is_a_unit_slip(E, unit, tmp_path):
    lo, hi = E_RANGE
    assert lo <= NYLON_E and hi >= DIAMOND_E, "the range holds the engineering solids, nylon to diamond"
    message = rf"`E` = {re.escape(f'{E:g}')} MPa lies outside \[1000, 1.5e\+06\] MPa.*{unit}"
    with pytest.raises(InputError, match=message):
        material_compliance(E, 0.3)
    with pytest.raises(ValueError, match=message):
        load_cases(None, _catalogue(tmp_path, material={"E": E, "nu": 0.3}))
    assert material_compliance(210e3, 0.3) == pytest.approx(_pair(210e3, 0.3), rel=SAME)


SOLVE = ["--R1", "10", "--R2", "5", "--b", "1", "--P", "400", "--s", "0.1", "--nu", "0.3"]


@pytest.mark.parametrize("argv", [
    ["solve", *SOLVE],
    ["solve", *SOLVE, "--rigid"],
    ["slip", *SOLVE, "--Q", "20", "--f", "0.5"],
    ["match", *SOLVE, "--Q", "20", "--f", "0.5", "--edge", "left", "--no-fatigue"],
    ["fatigue", *SOLVE, "--Q-max", "20", "--f", "0.5"],
    ["cycle", "--R1", "10", "--R2", "5", "--b", "1", "--nu", "0.3", "--f", "0.5",
     "--state0", "400,0.1,-20,0", "--state1", "400,0.1,20,0"],
    ["deck", "--case", "caseA_sym"],
], ids=lambda a: " ".join(a[:1] + a[-1:]))
@pytest.mark.parametrize("E", ["210e9", "210"])
def test_every_command_refuses_a_unit_slip_of_E_in_one_line(argv, E, capsys, tmp_path):
    assert main([*argv, "--E", E, "--out", str(tmp_path / "out")] if argv[0] in ("deck", "cycle")
                else [*argv, "--E", E]) == 2
    err = capsys.readouterr().err.strip()
    assert "\n" not in err and "`--E`" in err and "[1000, 1.5e+06] MPa" in err, err


def test_the_fe_normal_model_of_two_similar_bodies_is_a_block_of_half_their_modulus():
    """The one mapping (threepart.problem.material): the rigid punch's block of E/2 has the pair's A; the FE
    model run through the registry on the Ti flank has that A and the SIE's contact."""
    assert rigid_punch_modulus(similar_pair(E_TI, NU_TI), NU_TI) == pytest.approx(0.5 * E_TI, rel=SAME)
    assert TI.block_E == pytest.approx(0.5 * E_TI, rel=SAME)
    assert get_case("caseA_sym").block_E == pytest.approx(210e3, rel=SAME)      # a rigid punch: E itself
    fe = threepart.solve(TI.punch, TI.P, TI.s, A=TI.A, method="fem", nu=TI.nu, mesh="quick")
    assert fe.A == pytest.approx(TI.A, rel=SAME)
    ref = sie.solve_normal(TI.punch, TI.P, TI.s, A=_pair(E_TI, NU_TI))
    W = ref.a + ref.c
    assert abs(fe.a - ref.a) <= tolerance("fem-quick", "a").limit * W
    assert abs(fe.c - ref.c) <= tolerance("fem-quick", "c").limit * W


def test_the_calculix_deck_of_a_pair_is_a_block_of_half_the_modulus(tmp_path, capsys):
    from threepart import calculix

    out = tmp_path / "job.inp"
    assert main(["deck", "--case", "fan_blade_flank", "--h", "0.05", "--out", str(out)]) == 0
    printed = capsys.readouterr().out
    cards = calculix.parse_deck(out.read_text())
    moduli = [float(c.data[0][0]) for c in cards if c.name == "ELASTIC"]
    assert moduli[0] == pytest.approx(0.5 * E_TI, rel=SAME)           # the block
    k = calculix.DeckSettings().stiffening
    assert moduli[1] == pytest.approx(k * moduli[0], rel=SAME)         # the stiff punch
    # the model's own A: the block's rigid-punch A times (1 + 1/stiffening), i.e. the pair's
    A = float(printed.split("compliance A = ")[1].split()[0])
    assert A == pytest.approx(_pair(E_TI, NU_TI) * (1 + 1 / k), rel=PRINTED_A)
