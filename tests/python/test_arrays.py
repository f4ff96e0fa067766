"""Array handling of the vectorised API: dtypes, memory layouts, single vectors, broadcasting,
empty batches and the errors for malformed arrays."""

import numpy as np
import pytest

import bxdf
from conftest import random_directions


@pytest.fixture
def model():
    return bxdf.make("lambertian", reflectance=(0.8, 0.5, 0.2))


@pytest.fixture
def pairs(rng):
    return random_directions(rng, 257), random_directions(rng, 257)


@pytest.mark.parametrize("dtype", [np.float16, np.float32, np.float64, np.longdouble])
def test_any_float_dtype_gives_the_float32_result(model, pairs, dtype):
    wo, wi = pairs
    want = model.f(wo, wi)
    got = model.f(wo.astype(dtype), wi.astype(dtype))
    assert got.dtype == np.float32 and got.shape == (257, 3)
    tol = 1e-3 if dtype == np.float16 else 1e-6
    np.testing.assert_allclose(got, want, rtol=tol)


def test_integer_arrays_and_python_lists_are_accepted(model):
    np.testing.assert_allclose(model.f([0, 0, 1], [[1, 0, 1], [0, 2, 3]]), [[0.8 / np.pi, 0.5 / np.pi, 0.2 / np.pi]] * 2, rtol=1e-6)
    np.testing.assert_array_equal(model.f(np.array([0, 0, 1], np.int64), (0, 1, 1)), model.f([0.0, 0.0, 1.0], [0.0, 1.0, 1.0]))
    np.testing.assert_allclose(model.pdf(np.array([[0, 0, 1]], np.uint8), [0, 0, 1]), [1 / np.pi], rtol=1e-6)


def test_memory_layouts(model, pairs):
    wo, wi = pairs
    want = model.f(wo, wi)
    np.testing.assert_array_equal(model.f(np.asfortranarray(wo), np.asfortranarray(wi)), want)
    # Every other row of a bigger array, and a transposed view.
    big = np.zeros((2 * len(wo), 3), np.float64)
    big[::2] = wo
    np.testing.assert_array_equal(model.f(big[::2], wi), want)
    np.testing.assert_array_equal(model.f(np.ascontiguousarray(wo.T).T, wi), want)
    # Columns picked out of a wider array.
    wide = np.zeros((len(wo), 5), np.float32)
    wide[:, 1:4] = wo
    np.testing.assert_array_equal(model.f(wide[:, 1:4], wi), want)
    # Read-only input is fine; inputs are never written.
    ro = wo.copy()
    ro.setflags(write=False)
    np.testing.assert_array_equal(model.f(ro, wi), want)
    assert np.array_equal(ro, wo)


def test_single_vectors_keep_the_batch_axis(model):
    # Documented choice: results are never squeezed; (3,) inputs give N = 1.
    f = model.f([0, 0, 1], [0, 0.6, 0.8])
    assert f.shape == (1, 3)
    assert model.pdf([0, 0, 1], [0, 0.6, 0.8]).shape == (1,)
    wi, f, pdf = model.sample_f([0, 0, 1], [0.5, 0.5])
    assert wi.shape == (1, 3) and f.shape == (1, 3) and pdf.shape == (1,)
    assert model.rho([0, 0, 1], 16).shape == (1, 3)


def test_single_vectors_broadcast_against_batches(model, pairs, rng):
    wo, wi = pairs
    one = np.array([0.2, -0.3, 0.9], np.float32)
    want = model.f(np.tile(one, (len(wi), 1)), wi)
    np.testing.assert_array_equal(model.f(one, wi), want)
    np.testing.assert_array_equal(model.f(one[None, :], wi), want)
    np.testing.assert_array_equal(model.pdf(wi, one), model.pdf(wi, np.tile(one, (len(wi), 1))))
    u = rng.random((len(wo), 2))
    got = model.sample_f(one, u)
    ref = model.sample_f(np.tile(one, (len(wo), 1)), u)
    for g, r in zip(got, ref):
        np.testing.assert_array_equal(g, r)
    got = model.sample_f(wo, np.array([0.25, 0.75]))
    ref = model.sample_f(wo, np.tile([0.25, 0.75], (len(wo), 1)))
    for g, r in zip(got, ref):
        np.testing.assert_array_equal(g, r)


def test_empty_batches(model):
    empty = np.zeros((0, 3))
    assert model.f(empty, empty).shape == (0, 3)
    assert model.f(empty, [0, 0, 1]).shape == (0, 3)
    assert model.pdf(empty, empty).shape == (0,)
    wi, f, pdf = model.sample_f(empty, np.zeros((0, 2)))
    assert wi.shape == (0, 3) and f.shape == (0, 3) and pdf.shape == (0,)
    assert model.rho(empty, 4).shape == (0, 3)


@pytest.mark.parametrize(
    "wo, argument, words",
    [
        (np.zeros((4, 2)), "wo", ["(4, 2)", "(N, 3)"]),
        (np.zeros((4, 4)), "wo", ["(4, 4)"]),
        (np.zeros((2, 4, 3)), "wo", ["(2, 4, 3)"]),
        (np.zeros(4), "wo", ["(4,)"]),
        (np.float64(1.0), "wo", ["()"]),
        (np.zeros((3, 3), complex), "wo", ["complex"]),
        (np.zeros((3, 3), bool), "wo", ["bool"]),
        (np.array([["a", "b", "c"]]), "wo", ["dtype"]),
        ([[0, 0, 1], [0, 1]], "wo", []),
        (None, "wo", ["None"]),
        ("0 0 1", "wo", []),
    ],
)
def test_malformed_directions_are_value_errors_naming_the_argument(model, wo, argument, words):
    with pytest.raises(ValueError) as err:
        model.f(wo, [0, 0, 1])
    message = str(err.value)
    assert f"'{argument}'" in message
    for w in words:
        assert w in message, message
    with pytest.raises(ValueError, match="'wi'"):
        model.pdf([0, 0, 1], wo)


def test_mismatched_batch_sizes(model):
    with pytest.raises(ValueError, match=r"'wo' and 'wi'.*\(4 and 5\)"):
        model.f(np.zeros((4, 3)), np.zeros((5, 3)))
    with pytest.raises(ValueError, match=r"'wo' and 'u'"):
        model.sample_f(np.zeros((4, 3)), np.zeros((5, 2)))


@pytest.mark.parametrize("u", [[1.5, 0.2], [0.2, -0.1], [np.nan, 0.5], [0.5, np.inf], [[0.5, 0.5], [0.5, 2.0]]])
def test_u_must_be_finite_and_in_the_unit_square(model, u):
    with pytest.raises(ValueError, match=r"'u'.*\[0, 1\)"):
        model.sample_f([0, 0, 1], u)


def test_u_of_exactly_one_is_accepted(model):
    wi, f, pdf = model.sample_f([0, 0, 1], [1.0, 1.0])
    assert pdf[0] > 0 and np.all(np.isfinite(wi))


def test_u_shape_errors(model):
    with pytest.raises(ValueError, match=r"'u' has shape \(3,\)"):
        model.sample_f([0, 0, 1], [0.1, 0.2, 0.3])


def test_outputs_are_fresh_writable_float32_arrays(model):
    a = model.f([0, 0, 1], [0, 0, 1])
    b = model.f([0, 0, 1], [0, 0, 1])
    assert a.flags.c_contiguous and a.flags.writeable and a.dtype == np.float32
    a[:] = -1
    assert np.all(b >= 0)
