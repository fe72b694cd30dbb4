from setuptools import find_packages
from setuptools import setup

package_name = 'ament_urdf_validate'

setup(
    name=package_name,
    version='0.1.0',
    packages=find_packages(exclude=['test']),
    data_files=[
        ('share/' + package_name, ['package.xml']),
        ('share/ament_index/resource_index/packages', ['resource/' + package_name]),
    ],
    install_requires=['setuptools'],
    package_data={'': []},
    zip_safe=True,
    author='urdf-validator maintainers',
    maintainer='urdf-validator maintainers',
    url='https://github.com/urdf-validator/urdf-validator',
    keywords=['ROS'],
    classifiers=[
        'Intended Audience :: Developers',
        'Programming Language :: Python',
        'Topic :: Software Development',
    ],
    description='Check robot descriptions (URDF, xacro, SDFormat, MJCF) with urdf_validate.',
    long_description='An ament linter running urdf_validate on the robot descriptions of a ROS 2 package '
                     'and writing an xUnit result file for colcon test.',
    license='MIT',
    entry_points={
        'console_scripts': [
            'ament_urdf_validate = ament_urdf_validate.main:main',
        ],
        'pytest11': [
            'ament_urdf_validate = ament_urdf_validate.pytest_marker',
        ],
    },
)
