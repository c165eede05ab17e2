from glob import glob

from setuptools import find_packages, setup

package_name = 'olive_sim'

setup(
    name=package_name,
    version='0.1.0',
    packages=find_packages(exclude=['test']),
    package_data={package_name: ['static/*']},
    data_files=[
        ('share/ament_index/resource_index/packages', ['resource/' + package_name]),
        ('share/' + package_name, ['package.xml', 'README.md']),
        ('share/' + package_name + '/launch', glob('launch/*.launch.py')),
    ],
    install_requires=['setuptools'],
    zip_safe=False,
    maintainer='Owl Kit Lab',
    maintainer_email='team@owlkitlab.invalid',
    description='Simulated Olive modules (IMU, servo, camera) of the Owl Kit.',
    license='Apache-2.0',
    tests_require=['pytest'],
    entry_points={
        'console_scripts': [
            'imu_sim = olive_sim.imu_node:main',
            'servo_sim = olive_sim.servo_node:main',
            'camera_sim = olive_sim.camera_node:main',
            'kit_hosts = olive_sim.kit_hosts:main',
        ],
    },
)
