import netshape


def test_package_imports_core_areas():
    # every area submodule resolves and exposes the C++ submodule it re-exports
    for area in netshape._AREAS:
        mod = getattr(netshape, area)
        assert mod.__name__ == f"netshape.{area}"
