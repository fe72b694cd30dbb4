"""pytest plugin (entry point pytest11): registers the `urdf_validate` marker."""


def pytest_configure(config):
    config.addinivalue_line(
        'markers', 'urdf_validate: marks tests checking robot descriptions with urdf_validate')
