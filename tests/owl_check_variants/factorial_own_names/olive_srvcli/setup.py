from setuptools import setup

package_name = 'olive_srvcli'

setup(
    name=package_name,
    version='0.0.0',
    packages=[package_name],
    data_files=[
        ('share/ament_index/resource_index/packages', ['resource/' + package_name]),
        ('share/' + package_name, ['package.xml']),
    ],
    install_requires=['setuptools'],
    zip_safe=True,
    entry_points={
        'console_scripts': [
            'fact_service = olive_srvcli.fact_service:main',
            'fact_client = olive_srvcli.fact_client:main',
        ],
    },
)
