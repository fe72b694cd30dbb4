# test/test_urdf_validate.py of an ament_python package: `colcon test` runs it with pytest, in the
# package's source folder. Needs <test_depend>ament_urdf_validate</test_depend> in package.xml.
import pytest

from ament_urdf_validate.main import main_with_errors


@pytest.mark.linter
@pytest.mark.urdf_validate
def test_urdf_validate():
    rc, errors = main_with_errors(argv=[])
    assert rc == 0, 'urdf_validate found %d problem(s):\n' % len(errors) + '\n'.join(errors)
